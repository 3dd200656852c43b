"""read_frames: the frames of an atssim result file, safe while the run writes it.

atssim flushes every frame without SWMR (so that a killed run's file opens
with a plain h5py.File), and a read that lands inside a flush can fail or
see a row that is only half on disk. The writer records in /frames/flushed
how many frames are on disk in full, and writes that number only after the
flush that put them there. So read_frames reads rows below /frames/flushed
only, opening the file afresh for every read, and retries a read that fails
(the writer was mid-flush) with back-off until `timeout` seconds have passed.
Files written before /frames/flushed existed: a complete run's every frame,
else the rows that every /frames series has.
"""
import dataclasses
import time

import h5py
import numpy as np

# What a read inside a flush raises: HDF5's errors (OSError), a group or
# dataset not yet linked (KeyError), a shape or selection half-updated
# (ValueError, IndexError), h5py's RuntimeError for a broken B-tree node.
TRANSIENT = (OSError, KeyError, ValueError, IndexError, RuntimeError)


class ReadTimeout(OSError):
    """Every read failed for `timeout` seconds; the last failure is its __cause__."""


@dataclasses.dataclass
class Frames:
    first: int              # index of the first frame read (0 = the initial state)
    time: np.ndarray        # (F,) seconds
    positions: np.ndarray   # (F, N, 3) float32, every object's vertices (/mesh/<name> vertex_offset, vertex_count)
    flushed: int            # frames on disk in full when read (first + F when all were asked for)
    complete: bool          # the run ended well (root attribute `complete`)
    error: str              # why it failed, "" while running or when complete
    retries: int            # reads that failed and were tried again


def _attr_text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)


def _flushed(f: h5py.File) -> int:
    if "frames/flushed" in f:
        return int(f["frames/flushed"][0])
    n = min(f["frames/positions"].shape[0], f["frames/time"].shape[0])
    return n if int(f.attrs.get("complete", 0)) == 1 else max(n - 1, 0)


def _read(path, first: int, stop) -> Frames:
    with h5py.File(path, "r") as f:
        flushed = _flushed(f)
        end = flushed if stop is None else min(stop, flushed)
        begin = min(first, end)
        positions = f["frames/positions"][begin:end]
        times = f["frames/time"][begin:end]
        if positions.shape[0] != end - begin or times.shape[0] != end - begin:
            raise ValueError(f"read {positions.shape[0]} positions and {times.shape[0]} times of rows {begin}:{end}")
        return Frames(begin, times, positions, flushed, int(f.attrs.get("complete", 0)) == 1,
                      _attr_text(f.attrs.get("error", "")), 0)


def read_frames(path, first: int = 0, stop=None, *, timeout: float = 30.0) -> Frames:
    """Frames first … stop−1 (stop=None: every frame flushed so far) of an atssim
    result file, retrying with back-off (5 ms doubling to 0.5 s) while a read
    fails, for up to `timeout` seconds; then ReadTimeout."""
    deadline = time.monotonic() + timeout
    delay, retries = 0.005, 0
    while True:
        try:
            frames = _read(path, first, stop)
            frames.retries = retries
            return frames
        except FileNotFoundError:
            raise
        except TRANSIENT as e:
            if time.monotonic() + delay > deadline:
                raise ReadTimeout(f"{path}: no read succeeded in {timeout} s ({retries + 1} tries): {e}") from e
            retries += 1
            time.sleep(delay)
            delay = min(2 * delay, 0.5)


def follow_frames(path, *, interval: float = 0.1, timeout: float = 30.0, start_timeout: float = 60.0,
                  idle_timeout=None):
    """Yields Frames with the frames that are new since the last read, every
    `interval` seconds, until the run has ended (complete or failed) and every
    frame was yielded. Waits up to `start_timeout` seconds for the file to
    appear; `timeout` bounds each read's retries (read_frames). A killed run
    never ends: with `idle_timeout` (seconds) the generator returns when no
    new frame came for that long."""
    started = time.monotonic()
    last_new = started
    seen = 0
    while True:
        try:
            frames = read_frames(path, seen, timeout=timeout)
        except FileNotFoundError:
            if time.monotonic() - started < start_timeout:
                time.sleep(interval)
                continue
            raise
        if frames.time.shape[0]:
            seen = frames.first + frames.time.shape[0]
            last_new = time.monotonic()
            yield frames
        ended = frames.complete or frames.error != ""
        if ended and seen >= frames.flushed:
            return
        if idle_timeout is not None and time.monotonic() - last_new > idle_timeout:
            return
        time.sleep(interval)
