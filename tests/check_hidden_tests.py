#!/usr/bin/python3
"""Fails when a Catch2 test is hidden ("[.]", "[.tag]" or "[!hide]", which
ctest never runs) without a comment in the five lines above its tags naming
the issue of the project that will un-hide it ("issue #N"). A known failure
is an expected failure ("[!shouldfail]", run and counted), not hidden.
Also fails on a test whose name starts with '-': ctest passes the name to
the binary as its filter, and Catch2 takes it for an option (the test then
runs nothing).

usage: tests/check_hidden_tests.py TESTS_DIR"""
import pathlib
import re
import sys

HIDDEN = re.compile(r'"[^"\n]*\[(\.|!hide)[^"\n]*"')
ISSUE = re.compile(r"issue #\d+")
DASH = re.compile(r'TEST_CASE\(\s*"-')


def main() -> int:
    bad = []
    sources = sorted(pathlib.Path(sys.argv[1]).rglob("*.cpp"))
    if not sources:
        print(f"no test source under {sys.argv[1]}: nothing was checked")
        return 1
    for src in sources:
        lines = src.read_text(encoding="utf-8").splitlines()
        for k, line in enumerate(lines):
            if HIDDEN.search(line) and not any(ISSUE.search(l) for l in lines[max(0, k - 5):k + 1]):
                bad.append(f"{src}:{k + 1}: hidden test without a comment naming the issue that will un-hide it")
            if DASH.search(line):
                bad.append(f"{src}:{k + 1}: a test name starting with '-' (Catch2 takes the ctest filter for an option)")
    for b in bad:
        print(b)
    print(f"{len(bad)} hidden tests without an issue or names taken for options")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
