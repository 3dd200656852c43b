"""Shared helpers of the workflow tests: the real atssim binary, real tools.

Each test is a script that ctest runs; exit code 77 means "skipped" (ctest's
SKIP_RETURN_CODE), with the reason on stderr. A script that ends without
having made a single check() ran nothing, and fails.
"""
import atexit
import os
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
ATSSIM = os.environ.get("ATSSIM", "atssim")
SOURCE_DIR = os.environ.get("ATSSIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPTS = os.path.join(SOURCE_DIR, "scripts")


_checks = 0
_skipped = _failed = False


def _ran_nothing():
    if _checks == 0 and not _skipped and not _failed:
        print("FAILED: the test made no check: it ran nothing", file=sys.stderr, flush=True)
        os._exit(1)


atexit.register(_ran_nothing)


def skip(reason):
    global _skipped
    _skipped = True
    print(f"SKIPPED: {reason}", file=sys.stderr)
    sys.exit(SKIP)


def require_tool(name, install_hint):
    if shutil.which(name) is None:
        skip(f"'{name}' is not installed ({install_hint})")


def fail(message):
    global _failed
    _failed = True
    print(f"FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    global _checks
    _checks += 1
    if not condition:
        fail(message)


def scene(name):
    return os.path.join(SOURCE_DIR, "scenes", name + ".yaml")


def run(args, **kw):
    """Runs a command, echoing it; returns the CompletedProcess (text)."""
    print("$", " ".join(args), flush=True)
    return subprocess.run(args, text=True, capture_output=True, **kw)


def temp_dir():
    return tempfile.TemporaryDirectory(prefix="atssim-workflow-")
