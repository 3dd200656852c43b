"""Reading atssim results from Python, also while a run is writing them.

    import sys; sys.path.insert(0, "<atssim checkout>/python")
    import atssim
    f = atssim.read_frames("out.h5")            # every frame flushed so far
    f.time, f.positions, f.complete             # (F,), (F, N, 3), run status
    for f in atssim.follow_frames("out.h5"):    # new frames as the run writes them
        ...

docs/output-format.md, "Reading a file while it is written".
"""
from .frames import Frames, ReadTimeout, follow_frames, read_frames

__all__ = ["Frames", "ReadTimeout", "follow_frames", "read_frames"]
