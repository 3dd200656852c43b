#!/usr/bin/python3
"""The suite's counts from ctest's JUnit report (`ctest --output-junit FILE`):
tests, passed, failed, skipped (each named with its reason: the test's
"SKIPPED: …" line) and not run (disabled, or never started). scripts/test.sh
and scripts/check.sh print it after ctest; it fails when a test failed or
did not run, and when the report holds no test (a suite that ran nothing).

usage: scripts/suite_summary.py JUNIT.xml"""
import sys
import xml.etree.ElementTree as ET


def reason(case: ET.Element) -> str:
    """Why a test was skipped: its own "SKIPPED: …" line, else ctest's message."""
    out = case.findtext("system-out") or ""
    for line in out.splitlines():
        if line.startswith("SKIPPED:"):
            return line[len("SKIPPED:"):].strip()[:160]
    skipped = case.find("skipped")
    return (skipped.get("message") if skipped is not None else "") or "no reason given"


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        cases = list(ET.parse(sys.argv[1]).getroot().iter("testcase"))
    except (OSError, ET.ParseError) as e:
        print(f"suite summary: cannot read {sys.argv[1]}: {e}", file=sys.stderr)
        return 1
    passed, failed, skipped, not_run = [], [], [], []
    for case in cases:
        name, status = case.get("name", "?"), case.get("status", "")
        if status == "fail" or case.find("failure") is not None:
            failed.append(name)
        elif status == "run":
            passed.append(name)
        elif status == "notrun" and case.find("skipped") is not None:
            skipped.append(f"{name}: {reason(case)}")
        else:
            not_run.append(f"{name} ({status or 'no status'})")
    print(f"suite: {len(cases)} tests, {len(passed)} passed, {len(failed)} failed, {len(skipped)} skipped"
          + (f", {len(not_run)} not run" if not_run else ""))
    for s in skipped:
        print(f"  skipped {s}")
    for n in not_run:
        print(f"  not run {n}")
    for f in failed:
        print(f"  FAILED {f}")
    if not cases:
        print("suite summary: the report holds no test: the suite ran nothing", file=sys.stderr)
        return 1
    return 1 if failed or not_run else 0


if __name__ == "__main__":
    sys.exit(main())
