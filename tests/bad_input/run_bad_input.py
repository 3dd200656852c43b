#!/usr/bin/python3
"""The bad-input suite: every case through the real binary.

A case is a scene in cases/*.yaml whose last comment lines say what must
happen (`# exit: 2`; `# expect: {scene}:LINE:`, the file:line the message must
name, {scene} standing for the case's path; optionally `# says: TEXT`, what
it must say, `# args: run {scene} …` and `# setup: NAME`), or a line of
cli.txt or of a cli-*.txt beside it. A setup (setups.py) makes files at test time or an environment
around the case; a scene case with one is copied into the case's folder
first, so that the files it names are found there. For each case: the exit
code is the one expected, stderr is exactly one line, that line contains
the expected text (the file:line or option it names), stdout is empty, and
a case that fails with exit 2 wrote nothing: its folder holds the same files
with the same sizes and times afterwards.

    run_bad_input.py [NAME-SUBSTRING]      (ATSSIM = the binary)

Prints one line per case and the counts; fails when a case fails or when no
case ran (a filter that matches nothing, every case skipped).
"""
import contextlib
import os
import shlex
import shutil
import subprocess
import sys
import tempfile

from setups import SETUPS, Skip

HERE = os.path.dirname(os.path.abspath(__file__))
ATSSIM = os.environ.get("ATSSIM", "atssim")
if os.sep in ATSSIM:
    ATSSIM = os.path.abspath(ATSSIM)  # the cases run in folders of their own


def load_cases():
    """(name, exit code, expected texts, argv template, scene path or None, setup name or None)"""
    cases = []
    for name in sorted(os.listdir(os.path.join(HERE, "cases"))):
        path = os.path.join(HERE, "cases", name)
        meta = {}
        for line in open(path, encoding="utf-8", errors="replace"):
            if line.startswith(("# exit: ", "# expect: ", "# says: ", "# args: ", "# setup: ")):
                key, value = line[2:].rstrip("\n").split(": ", 1)
                meta[key] = value
        args = meta.get("args", "run {scene} -o {out}")
        expect = [meta["expect"]] + ([meta["says"]] if "says" in meta else [])
        cases.append((name[:-5], int(meta["exit"]), expect, shlex.split(args), path, meta.get("setup")))
    # cli.txt and every cli-*.txt beside it (one file per area, so that
    # branches adding cases do not edit the same lines).
    for listing in sorted(n for n in os.listdir(HERE) if n == "cli.txt" or (n.startswith("cli-") and n.endswith(".txt"))):
        for number, line in enumerate(open(os.path.join(HERE, listing)), 1):
            if not line.strip() or line.startswith("#"):
                continue
            code, expect, args = (part.strip() for part in line.split("|", 2))
            words = shlex.split(args)
            setup = words.pop(0)[1:] if words and words[0].startswith("@") else None
            cases.append((f"{listing}:{number}", int(code), [expect], words, None, setup))
    for case in cases:
        if case[5] is not None and case[5] not in SETUPS:
            sys.exit(f"{case[0]}: unknown setup '{case[5]}' (setups.py has {', '.join(SETUPS)})")
    return cases


def snapshot(folder):
    """Every path under `folder` with its size and modification time."""
    seen = {}
    for base, dirs, files in os.walk(folder):
        for entry in dirs + files:
            p = os.path.join(base, entry)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            seen[os.path.relpath(p, folder)] = (st.st_size, st.st_mtime_ns)
    return seen


def run_case(name, code, expect, args, scene, setup, tmp):
    """None when the case passes, "skip: why" when it cannot run here, else what went wrong."""
    out = os.path.join(tmp, "out.h5")
    env = dict(os.environ, POCL_CACHE_DIR=os.environ.get("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl")))
    with contextlib.ExitStack() as stack:
        extra = {}
        if setup is not None:
            try:
                extra = stack.enter_context(SETUPS[setup](tmp))
            except Skip as why:
                return f"skip: {why}"
            if scene is not None:
                scene = shutil.copy(scene, os.path.join(tmp, os.path.basename(scene)))
        env.update(extra.get("env", {}))
        values = {"scene": scene or "", "out": out, "tmp": tmp, "good": os.path.join(HERE, "good.yaml"),
                  "data": os.path.join(HERE, "data")}
        argv = extra.get("prefix", []) + [ATSSIM] + [a.format(**values) for a in args]
        expect = [e.format(**values) for e in expect]
        before = snapshot(tmp)
        try:
            r = subprocess.run(argv, capture_output=True, text=True, timeout=120, cwd=tmp, env=env)
        except subprocess.TimeoutExpired:
            return f"{name}: timed out: {shlex.join(argv)}"
        after = snapshot(tmp)
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
    if code == 2:
        written = sorted(p for p in after if before.get(p) != after[p])
        if written:
            problems.append(f"it wrote {', '.join(written)}")
    if problems:
        return f"{name}: {'; '.join(problems)}\n    $ {shlex.join(argv)}\n    stderr: {r.stderr.strip()[:600]}"
    return None


def main():
    only = sys.argv[1] if len(sys.argv) > 1 else ""
    cases = [c for c in load_cases() if only in c[0]]
    failures, skipped = [], []
    for name, code, expect, args, scene, setup in cases:
        with tempfile.TemporaryDirectory(prefix="atssim-bad-input-") as tmp:
            result = run_case(name, code, expect, args, scene, setup, tmp)
        if result is not None and result.startswith("skip: "):
            skipped.append(f"{name} ({result[6:]})")
            print(f"skip {name}: {result[6:]}", flush=True)
            continue
        print(("FAIL " if result else "ok   ") + name, flush=True)
        if result:
            failures.append(result)
    ran = len(cases) - len(skipped)
    print(f"{ran - len(failures)} of {ran} bad-input cases pass, {len(skipped)} skipped"
          + (f": {'; '.join(skipped)}" if skipped else ""))
    for f in failures:
        print(f, file=sys.stderr)
    if ran == 0:
        print(f"no bad-input case ran (filter {only!r}, {len(cases)} matched, {len(skipped)} skipped)", file=sys.stderr)
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
