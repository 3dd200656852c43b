#pragma once
// Ctrl-C and SIGTERM for `atssim run`, taken by a thread of their own
// (sigwait) instead of a handler that runs on whichever thread the kernel
// picks. Both signals are blocked in every other thread, so the OpenCL
// driver's workers and its in-process compiler never see them: LLVM, which
// pocl runs to build the kernels, deletes its temporary files on SIGINT,
// and the build then fails with the driver's own lines on stderr. Child
// processes inherit the mask. The first signal asks the run to stop
// (request_stop); a second one ends the process at once with exit code 130.
namespace atssim::app {

// Call before any other thread exists (at the start of a command).
void watch_stop_signals();

}  // namespace atssim::app
