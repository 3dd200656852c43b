#pragma once
// HDF5's own error stack never reaches the user: its automatic printing is
// turned off, and a failure becomes one line naming what atssim was doing
// and the innermost cause HDF5 recorded (often the system's, e.g. "No space
// left on device").
#include <string>

namespace atssim::io {

// Turns off HDF5's automatic error printing (idempotent; every entry point
// of lib/io calls it before its first HDF5 call).
void quiet_hdf5();

// For the command line, before any other HDF5 call: quiet_hdf5(), and no
// flush of open files at exit (H5dont_atexit): a file whose writes failed is
// abandoned as its last good flush left it (ResultWriter::fail).
void init_hdf5_for_command_line();

// The innermost message of HDF5's current error stack, with the system
// error HDF5 saw where it recorded one; "" when the stack is empty.
std::string hdf5_failure();

}  // namespace atssim::io
