#!/usr/bin/python3
"""Counts and names the known failures of the suite: Catch2 tests tagged
[!shouldfail] (run by ctest, which passes them while they fail and fails
them once they pass) and hidden tests ([.], never run by ctest; each names
its issue, tests/check_hidden_tests.py). Printed after ctest by
scripts/test.sh, so the suite's output says how many failures it knows of.

usage: scripts/expected_failures.py [BUILD_DIR]   (default build/release)"""
import pathlib
import subprocess
import sys


def names(binary: pathlib.Path, spec: str) -> list[str]:
    out = subprocess.run([str(binary), "--list-test-names-only", spec], capture_output=True, text=True)
    return [line.strip() for line in out.stdout.splitlines() if line.strip()]


def main() -> int:
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build/release")
    binaries = sorted(p for p in (build / "tests").glob("*/test_*") if p.is_file() and p.stat().st_mode & 0o111)
    expected, hidden = [], []
    for b in binaries:
        expected += [f"{b.name}: {n}" for n in names(b, "[!shouldfail]")]
        hidden += [f"{b.name}: {n}" for n in names(b, "[.]")]
    print(f"expected failures ([!shouldfail], run by ctest): {len(expected)}")
    for n in expected:
        print(f"  {n}")
    print(f"hidden tests ([.], not run by ctest): {len(hidden)}")
    for n in hidden:
        print(f"  {n}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
