#pragma once
// A file driver that keeps the output readable when the writer is killed in
// the middle of a flush.
//
// HDF5 (without SWMR) writes a flush in address order and the superblock,
// which holds the end-of-allocation address (EOA), last. A SIGKILL between
// the two leaves metadata that points at space allocated after the EOA the
// superblock still claims, and every read of the newest chunk fails ("addr
// overflow") -- the whole `f["frames/positions"][()]` of a killed run.
// This driver passes everything through to HDF5's sec2 driver, except that
// the EOA it reports for the superblock runs `reserve` bytes ahead of what
// is allocated, and the file is extended (sparsely) to that address before
// the superblock claiming it is written. A torn flush that allocated less
// than the reserve then references nothing beyond the claimed EOA. The
// reserve grows to twice the largest growth seen between two flushes.
// (Metadata written in place can still tear; see docs/architecture.md.)
#include <hdf5.h>

namespace atssim::io {

// Sets the driver on a file access property list.
void use_reserve_driver(hid_t fapl);

// Before H5Fflush on a file opened with the driver: sizes the reserve from
// the growth since the last call (at least `minimum` bytes) and extends the
// file ahead of the allocated space when the reserve has shrunk below it.
// A file opened with another driver is left alone.
void prepare_flush(hid_t file, hsize_t minimum);

}  // namespace atssim::io
