#!/usr/bin/python3
"""The bad-input suite: every case through the real binary.

A case is a scene in cases/*.yaml whose last comment lines say what must
happen (`# exit: 2`; `# expect: {scene}:LINE:`, the file:line the message must
name, {scene} standing for the case's path; optionally `# says: TEXT`, what
it must say, and `# args: run {scene} …`), or a line of cli.txt or of a
cli-*.txt beside it. For each: the exit
code is the one expected, stderr is exactly one line, that line contains the
expected text (the file:line it names), stdout is empty, and a case that
fails with exit 2 wrote no output file.

    run_bad_input.py [NAME-SUBSTRING]      (ATSSIM = the binary)
"""
import os
import shlex
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ATSSIM = os.environ.get("ATSSIM", "atssim")


def load_cases():
    cases = []
    for name in sorted(os.listdir(os.path.join(HERE, "cases"))):
        path = os.path.join(HERE, "cases", name)
        meta = {}
        for line in open(path, encoding="utf-8", errors="replace"):
            if line.startswith(("# exit: ", "# expect: ", "# says: ", "# args: ")):
                key, value = line[2:].rstrip("\n").split(": ", 1)
                meta[key] = value
        args = meta.get("args", "run {scene} -o {out}")
        expect = [meta["expect"]] + ([meta["says"]] if "says" in meta else [])
        cases.append((name[:-5], int(meta["exit"]), expect, shlex.split(args), path))
    # cli.txt and every cli-*.txt beside it (one file per area, so that
    # branches adding cases do not edit the same lines).
    for listing in sorted(n for n in os.listdir(HERE) if n == "cli.txt" or (n.startswith("cli-") and n.endswith(".txt"))):
        for number, line in enumerate(open(os.path.join(HERE, listing)), 1):
            if not line.strip() or line.startswith("#"):
                continue
            code, expect, args = (part.strip() for part in line.split("|", 2))
            cases.append((f"{listing}:{number}", int(code), [expect], shlex.split(args), None))
    return cases


def run_case(name, code, expect, args, scene, tmp):
    out = os.path.join(tmp, "out.h5")
    values = {"scene": scene or "", "out": out, "tmp": tmp, "good": os.path.join(HERE, "good.yaml"),
              "data": os.path.join(HERE, "data")}
    argv = [ATSSIM] + [a.format(**values) for a in args]
    expect = [e.format(**values) for e in expect]
    env = dict(os.environ, POCL_CACHE_DIR=os.environ.get("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl")))
    try:
        r = subprocess.run(argv, capture_output=True, text=True, timeout=120, cwd=tmp, env=env)
    except subprocess.TimeoutExpired:
        return f"{name}: timed out: {shlex.join(argv)}"
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    problems = []
    if r.returncode != code:
        problems.append(f"exit {r.returncode}, expected {code}")
    if len(lines) != 1:
        problems.append(f"{len(lines)} lines on stderr, expected exactly one")
    for e in expect:
        if e not in r.stderr:
            problems.append(f"stderr does not contain {e!r}")
    if r.stdout.strip():
        problems.append(f"stdout is not empty: {r.stdout[:200]!r}")
    if code == 2 and os.path.exists(out):
        problems.append("an output file was written")
    if problems:
        return f"{name}: {'; '.join(problems)}\n    $ {shlex.join(argv)}\n    stderr: {r.stderr.strip()[:600]}"
    return None


def main():
    only = sys.argv[1] if len(sys.argv) > 1 else ""
    cases = [c for c in load_cases() if only in c[0]]
    failures = []
    for name, code, expect, args, scene in cases:
        with tempfile.TemporaryDirectory(prefix="atssim-bad-input-") as tmp:
            failure = run_case(name, code, expect, args, scene, tmp)
        print(("FAIL " if failure else "ok   ") + name, flush=True)
        if failure:
            failures.append(failure)
    print(f"{len(cases) - len(failures)} of {len(cases)} bad-input cases pass")
    for f in failures:
        print(f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
