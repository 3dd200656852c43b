#include "io/h5_series.hpp"

namespace atssim::io {

H5Handle create_series(hid_t parent, const std::string& name, std::size_t rows, std::size_t cols, hid_t file_type) {
  const int rank = cols == 0 ? 1 : 3;
  hsize_t dims[3] = {0, rows, cols};
  hsize_t max[3] = {H5S_UNLIMITED, rows, cols};
  hsize_t chunk[3] = {hsize_t(cols == 0 ? 256 : 1), rows, cols};
  H5Handle space = h5_check(H5Screate_simple(rank, dims, max), H5Sclose, "series space");
  H5Handle props = h5_check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
  h5_check(H5Pset_chunk(props, rank, chunk), "chunking " + name);
  return h5_check(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, props, H5P_DEFAULT), H5Dclose,
                  "creating " + name);
}

hsize_t rows_of(hid_t set) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  hsize_t dims[3] = {0, 0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  return dims[0];
}

void truncate_rows(hid_t set, hsize_t rows) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  hsize_t dims[3] = {0, 0, 0};
  const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
  if (rank < 1 || dims[0] == rows) return;
  dims[0] = rows;
  h5_check(H5Dset_extent(set, dims), "truncating a series");
}

void append_series_rows(hid_t set, const void* values, std::size_t count, hid_t mem_type, hsize_t rows) {
  if (count == 0) return;
  const hsize_t size[1] = {rows + count};
  h5_check(H5Dset_extent(set, size), "extending a series");
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  const hsize_t start[1] = {rows}, n[1] = {count};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, n, nullptr), "selecting rows");
  H5Handle mem = h5_check(H5Screate_simple(1, n, nullptr), H5Sclose, "memory space");
  h5_check(H5Dwrite(set, mem_type, mem, space, H5P_DEFAULT, values), "writing rows of a series");
}

}  // namespace atssim::io
