"""What some bad-input cases need around them (run_bad_input.py): files made
at test time (large ones, a FIFO) rather than committed, and environments
(no OpenCL platform, a read-only file system, a folder the run may not
write). A case names its setup with `# setup: NAME` (a scene case) or
`@NAME` before the arguments (a line of cli.txt).

Each setup is a context manager over the case's fresh folder `tmp`; it
yields a dict with optional "env" (variables to set) and "prefix" (argv
words put before the binary), and raises Skip when this machine cannot
build the environment (the runner counts and names skipped cases).
"""
import contextlib
import os
import random
import shutil
import subprocess


class Skip(Exception):
    pass


# A square of two triangles: the lines every generated OBJ starts with.
OBJ_HEAD = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"


@contextlib.contextmanager
def huge_obj_nan(tmp):
    """huge.obj: 400,003 vertex lines (6 MB), the last one NaN (line 400,006) and in a face."""
    with open(os.path.join(tmp, "huge.obj"), "w") as f:
        f.write(OBJ_HEAD)
        f.writelines(f"v {i % 1000} {i // 1000} 0\n" for i in range(399_999))
        f.write("v 0 nan 0\nf 1 2 400004\n")
    yield {}


@contextlib.contextmanager
def huge_sparse_mesh(tmp):
    """huge.obj: a 9 GiB sparse file (no disk used): past the 8 GiB a mesh may have."""
    with open(os.path.join(tmp, "huge.obj"), "wb") as f:
        f.write(OBJ_HEAD.encode())
        f.truncate(9 << 30)
    yield {}


@contextlib.contextmanager
def huge_sparse_scene(tmp):
    """huge.yaml: a 100 MiB sparse scene file, past the 64 MiB a scene may have."""
    with open(os.path.join(tmp, "huge.yaml"), "wb") as f:
        f.write(b"simulation: {fps: 60}\n")
        f.truncate(100 << 20)
    yield {}


@contextlib.contextmanager
def garbage_mesh(tmp):
    """garbage.obj: 2 MB of random bytes (seeded)."""
    rng = random.Random(24)
    with open(os.path.join(tmp, "garbage.obj"), "wb") as f:
        f.write(bytes(rng.getrandbits(8) for _ in range(2 << 20)))
    yield {}


@contextlib.contextmanager
def fifo_mesh(tmp):
    """pipe.obj: a FIFO nobody writes to (reading it would block for ever)."""
    os.mkfifo(os.path.join(tmp, "pipe.obj"))
    yield {}


@contextlib.contextmanager
def no_opencl(tmp):
    """OCL_ICD_VENDORS at an empty folder: the ICD loader finds no platform."""
    empty = os.path.join(tmp, "no-icd")
    os.mkdir(empty)
    yield {"env": {"OCL_ICD_VENDORS": empty}}


@contextlib.contextmanager
def readonly_fs(tmp):
    """tmp/ro: a read-only tmpfs (mounted when root; skipped otherwise)."""
    ro = os.path.join(tmp, "ro")
    os.mkdir(ro)
    if os.geteuid() != 0 or not shutil.which("mount"):
        raise Skip("mounting a read-only file system needs root")
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "ro,size=64k", "tmpfs", ro], capture_output=True, text=True)
    if r.returncode != 0:
        raise Skip(f"mount -t tmpfs failed: {r.stderr.strip()}")
    try:
        yield {}
    finally:
        subprocess.run(["umount", ro], capture_output=True)


@contextlib.contextmanager
def unwritable_folder(tmp):
    """tmp/locked: a folder without write permission. Root may write anywhere, so
    as root the run is made as user nobody (setpriv), with tmp readable to it."""
    locked = os.path.join(tmp, "locked")
    os.mkdir(locked)
    os.chmod(locked, 0o555)
    prefix = []
    if os.geteuid() == 0:
        if not shutil.which("setpriv"):
            raise Skip("as root, the run needs setpriv to drop its rights")
        os.chmod(tmp, 0o755)
        prefix = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
    elif os.access(locked, os.W_OK):
        raise Skip("this user may write into a folder without write permission")
    try:
        yield {"prefix": prefix}
    finally:
        os.chmod(locked, 0o755)


@contextlib.contextmanager
def lock_folder(tmp):
    """out.h5.lock, where the run takes its lock, is a folder."""
    os.mkdir(os.path.join(tmp, "out.h5.lock"))
    yield {}


@contextlib.contextmanager
def sidecar_folder(tmp):
    """out.xdmf, the sidecar's name, is a folder."""
    os.mkdir(os.path.join(tmp, "out.xdmf"))
    yield {}


@contextlib.contextmanager
def plain_output(tmp):
    """out.h5 is a text file, not an HDF5 result."""
    with open(os.path.join(tmp, "out.h5"), "w") as f:
        f.write("not a result\n")
    yield {}


SETUPS = {f.__name__: f for f in (huge_obj_nan, huge_sparse_mesh, huge_sparse_scene, garbage_mesh, fifo_mesh,
                                  no_opencl, readonly_fs, unwritable_folder, lock_folder, sidecar_folder,
                                  plain_output)}
