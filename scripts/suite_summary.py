#!/usr/bin/python3
"""The suite's counts from ctest's JUnit report (`ctest --output-junit FILE`):
tests run, passed, failed, skipped (each skipped test named with the first
line of its reason) and not run. scripts/test.sh and scripts/check.sh print
it after ctest; a report that holds no test fails (a suite that ran nothing).

usage: scripts/suite_summary.py JUNIT.xml"""
import sys
import xml.etree.ElementTree as ET


def reason(case: ET.Element) -> str:
    """The skip message, else the last non-empty output line (the test's own reason)."""
    skipped = case.find("skipped")
    text = (skipped.get("message") if skipped is not None else "") or ""
    if not text.strip() or text.strip().lower() in ("skipped", "skip"):
        out = case.findtext("system-out") or ""
        lines = [l.strip() for l in out.splitlines() if l.strip()]
        text = lines[-1] if lines else ""
    return text.strip().splitlines()[0][:160] if text.strip() else "no reason given"


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        cases = ET.parse(sys.argv[1]).getroot().iter("testcase")
    except (OSError, ET.ParseError) as e:
        print(f"suite summary: cannot read {sys.argv[1]}: {e}", file=sys.stderr)
        return 1
    passed, failed, skipped, not_run = [], [], [], []
    for case in cases:
        name, status = case.get("name", "?"), case.get("status", "")
        if status == "fail" or case.find("failure") is not None:
            failed.append(name)
        elif status in ("notrun", "disabled") and case.find("skipped") is not None and "Skipped" not in (
                case.find("skipped").get("message") or "Skipped"):
            not_run.append(name)
        elif status in ("notrun", "disabled"):
            skipped.append(f"{name}: {reason(case)}")
        else:
            passed.append(name)
    total = len(passed) + len(failed) + len(skipped) + len(not_run)
    print(f"suite: {total} tests, {len(passed)} passed, {len(failed)} failed, {len(skipped)} skipped"
          + (f", {len(not_run)} not run" if not_run else ""))
    for s in skipped:
        print(f"  skipped {s}")
    for n in not_run:
        print(f"  not run {n}")
    for f in failed:
        print(f"  FAILED {f}")
    if total == 0:
        print("suite summary: the report holds no test: the suite ran nothing", file=sys.stderr)
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
