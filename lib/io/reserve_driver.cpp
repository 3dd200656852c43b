#include "io/reserve_driver.hpp"

#include <H5FDsec2.h>

#include <algorithm>
#include <cstdlib>
#include <new>

#include "io/h5_handle.hpp"

namespace atssim::io {

namespace {

struct ReserveFile {
  H5FD_t pub;  // first: HDF5 sees this part
  H5FD_t* inner = nullptr;
  haddr_t eoa = 0;       // what HDF5 has allocated
  haddr_t ahead = 0;     // what the superblock claims; the file is at least this long
  haddr_t last_eoa = 0;  // the EOA at the previous prepare_flush
  hsize_t reserve = 0;
};

ReserveFile* of(H5FD_t* f) { return reinterpret_cast<ReserveFile*>(f); }
const ReserveFile* of(const H5FD_t* f) { return reinterpret_cast<const ReserveFile*>(f); }

// The inner driver's EOA bounds its reads and sets the file's length at
// truncate: never below what the superblock may claim.
herr_t sync_inner(ReserveFile* f) { return H5FDset_eoa(f->inner, H5FD_MEM_DEFAULT, std::max(f->eoa, f->ahead)); }

H5FD_t* open(const char* name, unsigned flags, hid_t, haddr_t maxaddr) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) return nullptr;
  H5FD_t* inner = H5Pset_fapl_sec2(fapl) < 0 ? nullptr : H5FDopen(name, flags, fapl, maxaddr);
  H5Pclose(fapl);
  if (inner == nullptr) return nullptr;
  auto* f = new (std::nothrow) ReserveFile();
  if (f == nullptr) {
    H5FDclose(inner);
    return nullptr;
  }
  f->inner = inner;
  f->eoa = H5FDget_eoa(inner, H5FD_MEM_DEFAULT);
  return &f->pub;
}

herr_t close(H5FD_t* file) {
  ReserveFile* f = of(file);
  const herr_t rc = H5FDclose(f->inner);
  delete f;
  return rc;
}

int cmp(const H5FD_t* a, const H5FD_t* b) { return H5FDcmp(of(a)->inner, of(b)->inner); }

herr_t query(const H5FD_t* file, unsigned long* flags) {
  if (file == nullptr) {
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
    return 0;
  }
  if (H5FDquery(of(file)->inner, flags) < 0) return -1;
  // The handle is this driver's, not a POSIX descriptor, and SWMR is not offered.
  *flags &= ~(H5FD_FEAT_POSIX_COMPAT_HANDLE | H5FD_FEAT_SUPPORTS_SWMR_IO);
  return 0;
}

// The superblock encodes the EOA it asks for with H5FD_MEM_SUPER; every
// allocation asks with the type it allocates.
haddr_t get_eoa(const H5FD_t* file, H5FD_mem_t type) {
  const ReserveFile* f = of(file);
  return type == H5FD_MEM_SUPER ? std::max(f->eoa, f->ahead) : f->eoa;
}

herr_t set_eoa(H5FD_t* file, H5FD_mem_t, haddr_t addr) {
  ReserveFile* f = of(file);
  f->eoa = addr;
  return sync_inner(f);
}

haddr_t get_eof(const H5FD_t* file, H5FD_mem_t type) { return H5FDget_eof(of(file)->inner, type); }

herr_t get_handle(H5FD_t* file, hid_t, void** handle) {
  *handle = file;
  return 0;
}

herr_t read(H5FD_t* file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size, void* buf) {
  return H5FDread(of(file)->inner, type, dxpl, addr, size, buf);
}

herr_t write(H5FD_t* file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size, const void* buf) {
  return H5FDwrite(of(file)->inner, type, dxpl, addr, size, buf);
}

herr_t flush(H5FD_t* file, hid_t dxpl, hbool_t closing) { return H5FDflush(of(file)->inner, dxpl, closing); }

// Never shorter than the EOA a superblock on disk may claim: a file that
// ends before its superblock's EOA does not open ("truncated file").
herr_t truncate(H5FD_t* file, hid_t dxpl, hbool_t closing) {
  ReserveFile* f = of(file);
  if (sync_inner(f) < 0) return -1;
  return H5FDtruncate(f->inner, dxpl, closing);
}

herr_t lock(H5FD_t* file, hbool_t rw) { return H5FDlock(of(file)->inner, rw); }
herr_t unlock(H5FD_t* file) { return H5FDunlock(of(file)->inner); }

H5FD_class_t make_class() {
  H5FD_class_t c{};
  c.name = "atssim_reserve";
  c.maxaddr = (haddr_t(1) << (8 * sizeof(off_t) - 1)) - 1;
  c.fc_degree = H5F_CLOSE_WEAK;
  c.open = open;
  c.close = close;
  c.cmp = cmp;
  c.query = query;
  c.get_eoa = get_eoa;
  c.set_eoa = set_eoa;
  c.get_eof = get_eof;
  c.get_handle = get_handle;
  c.read = read;
  c.write = write;
  c.flush = flush;
  c.truncate = truncate;
  c.lock = lock;
  c.unlock = unlock;
  const H5FD_mem_t map[H5FD_MEM_NTYPES] = H5FD_FLMAP_DICHOTOMY;
  std::copy(map, map + H5FD_MEM_NTYPES, c.fl_map);
  return c;
}

hid_t driver_id() {
  static const H5FD_class_t cls = make_class();
  static hid_t id = -1;
  if (id < 0 || H5Iis_valid(id) <= 0) id = H5FDregister(&cls);
  return id;
}

}  // namespace

void use_reserve_driver(hid_t fapl) {
  const hid_t id = driver_id();
  h5_check(id < 0 ? herr_t(-1) : herr_t(0), "registering the output file driver");
  h5_check(H5Pset_driver(fapl, id, nullptr), "setting the output file driver");
}

void prepare_flush(hid_t file, hsize_t minimum) {
  H5Handle fapl = h5_check(H5Fget_access_plist(file), H5Pclose, "the output file's access properties");
  if (H5Pget_driver(fapl) != driver_id()) return;  // another driver: nothing to reserve
  void* handle = nullptr;
  h5_check(H5Fget_vfd_handle(file, H5P_DEFAULT, &handle), "the output file's driver");
  ReserveFile* f = of(static_cast<H5FD_t*>(handle));
  const hsize_t grown = f->eoa > f->last_eoa ? f->eoa - f->last_eoa : 0;
  f->last_eoa = f->eoa;
  f->reserve = std::max({f->reserve, minimum, 2 * grown});
  if (f->eoa + f->reserve <= f->ahead) return;
  // Extend the file first: the superblock may claim the new address only
  // once the file reaches it.
  f->ahead = f->eoa + 2 * f->reserve;
  h5_check(sync_inner(f), "extending the output file");
  h5_check(H5FDtruncate(f->inner, H5P_DEFAULT, false), "extending the output file");
}

}  // namespace atssim::io
