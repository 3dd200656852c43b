#include "io/checkpoint.hpp"

#include <array>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

namespace {

constexpr int kSlots = 2;
constexpr int kFields = 6;  // frame, frames_written, schedule_rows, wait_rows, makespan_rows, hash

std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

// FNV-1a over 8-byte little-endian words, then the tail byte by byte: one
// multiply per 8 bytes rather than per byte (the carried lists of a large
// surface are tens of megabytes a frame).
std::uint64_t fnv1a_words(std::uint64_t h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  const std::size_t words = size / 8;
  for (std::size_t i = 0; i < words; ++i) {
    std::uint64_t w = 0;
    for (int k = 7; k >= 0; --k) w = (w << 8) | p[8 * i + std::size_t(k)];
    h = (h ^ w) * 1099511628211ull;
  }
  return fnv1a(h, p + 8 * words, size - 8 * words);
}

using Hash = std::uint64_t (*)(std::uint64_t, const void*, std::size_t);

// `hash` over the fields and the state; fnv1a_words since the carried lists
// grew, fnv1a in files written before (still read).
std::uint64_t hash_of(const Checkpoint& c, Hash hash = fnv1a_words) {
  std::uint64_t h = 14695981039346656037ull;
  const long long fields[5] = {c.frame, c.frames_written, c.schedule_rows, c.wait_rows, c.makespan_rows};
  h = fnv1a(h, fields, sizeof fields);
  h = hash(h, c.positions.data(), c.positions.size());
  h = hash(h, c.velocities.data(), c.velocities.size());
  return hash(h, c.carried.data(), c.carried.size());  // (nothing for a file without it: the same hash)
}

std::array<long long, kSlots * kFields> read_index(hid_t index) {
  std::array<long long, kSlots * kFields> rows{};
  h5_check(H5Dread(index, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()), "reading /checkpoint/index");
  return rows;
}

// Selects columns [first, first + cols) of row `slot` of a [2, n] dataset.
H5Handle row_space(hid_t set, int slot, hsize_t cols, hsize_t first = 0) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "checkpoint space");
  const hsize_t start[2] = {static_cast<hsize_t>(slot), first}, count[2] = {1, cols};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting a checkpoint slot");
  return space;
}

}  // namespace

CheckpointSlots CheckpointSlots::create(hid_t file, std::size_t position_bytes, std::size_t velocity_bytes,
                                        std::size_t carried_bytes) {
  CheckpointSlots s;
  s.position_bytes_ = position_bytes;
  s.velocity_bytes_ = velocity_bytes;
  s.carried_bytes_ = carried_bytes;
  H5Handle group = create_group(file, "checkpoint");
  write_int_attribute(group, "positions_bytes", static_cast<long long>(position_bytes));
  write_int_attribute(group, "velocities_bytes", static_cast<long long>(velocity_bytes));
  write_int_attribute(group, "carried_bytes", static_cast<long long>(carried_bytes));
  const hsize_t state_dims[2] = {kSlots, std::max<hsize_t>(1, s.state_bytes())};
  H5Handle state_space = h5_check(H5Screate_simple(2, state_dims, nullptr), H5Sclose, "checkpoint space");
  s.state_ = h5_check(H5Dcreate2(group, "state", H5T_STD_U8LE, state_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      H5Dclose, "creating /checkpoint/state");
  const hsize_t index_dims[2] = {kSlots, kFields};
  H5Handle index_space = h5_check(H5Screate_simple(2, index_dims, nullptr), H5Sclose, "checkpoint space");
  s.index_ = h5_check(H5Dcreate2(group, "index", H5T_STD_I64LE, index_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      H5Dclose, "creating /checkpoint/index");
  std::array<long long, kSlots * kFields> empty{};
  for (int k = 0; k < kSlots; ++k) empty[k * kFields] = -1;
  h5_check(H5Dwrite(s.index_, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, empty.data()),
           "writing /checkpoint/index");
  return s;
}

std::optional<CheckpointSlots> CheckpointSlots::open(hid_t file) {
  if (H5Lexists(file, "checkpoint", H5P_DEFAULT) <= 0) return std::nullopt;
  CheckpointSlots s;
  H5Handle group = h5_check(H5Gopen2(file, "checkpoint", H5P_DEFAULT), H5Gclose, "opening /checkpoint");
  for (auto [name, out] :
       {std::pair{"positions_bytes", &s.position_bytes_}, {"velocities_bytes", &s.velocity_bytes_}}) {
    H5Handle attr = h5_check(H5Aopen(group, name, H5P_DEFAULT), H5Aclose, name);
    long long v = 0;
    h5_check(H5Aread(attr, H5T_NATIVE_LLONG, &v), name);
    *out = static_cast<std::size_t>(v);
  }
  // (0 in a file written before atssim kept the carried state.)
  s.carried_bytes_ = static_cast<std::size_t>(read_int_attribute(group, "carried_bytes"));
  s.state_ = h5_check(H5Dopen2(group, "state", H5P_DEFAULT), H5Dclose, "opening /checkpoint/state");
  s.index_ = h5_check(H5Dopen2(group, "index", H5P_DEFAULT), H5Dclose, "opening /checkpoint/index");
  const auto rows = read_index(s.index_);
  s.next_slot_ = rows[0] <= rows[kFields] ? 0 : 1;  // overwrite the older one
  return s;
}

void CheckpointSlots::write(const Checkpoint& c) {
  if (c.positions.size() != position_bytes_ || c.velocities.size() != velocity_bytes_ ||
      c.carried.size() != carried_bytes_) {
    throw std::logic_error(fmt::format("checkpoint: state of {}+{}+{} bytes, the file holds {}+{}+{}",
                                       c.positions.size(), c.velocities.size(), c.carried.size(), position_bytes_,
                                       velocity_bytes_, carried_bytes_));
  }
  const int slot = next_slot_;
  // The three parts written where they lie, each into its columns of the
  // slot's row, rather than joined into one copy first.
  hsize_t first = 0;
  for (const std::vector<std::byte>* part : {&c.positions, &c.velocities, &c.carried}) {
    if (part->empty()) continue;
    const hsize_t cols = part->size();
    H5Handle space = row_space(state_, slot, cols, first);
    const hsize_t count[2] = {1, cols};
    H5Handle mem = h5_check(H5Screate_simple(2, count, nullptr), H5Sclose, "checkpoint memory");
    h5_check(H5Dwrite(state_, H5T_NATIVE_UCHAR, mem, space, H5P_DEFAULT, part->data()), "writing /checkpoint/state");
    first += cols;
  }
  const std::uint64_t hash = hash_of(c);
  long long fields[kFields] = {c.frame, c.frames_written, c.schedule_rows, c.wait_rows, c.makespan_rows, 0};
  std::memcpy(&fields[5], &hash, sizeof hash);
  H5Handle ispace = row_space(index_, slot, kFields);
  const hsize_t icount[2] = {1, kFields};
  H5Handle imem = h5_check(H5Screate_simple(2, icount, nullptr), H5Sclose, "checkpoint memory");
  h5_check(H5Dwrite(index_, H5T_NATIVE_LLONG, imem, ispace, H5P_DEFAULT, fields), "writing /checkpoint/index");
  next_slot_ = 1 - slot;
}

std::optional<Checkpoint> CheckpointSlots::newest(long long frames_available, int* slot_found) const {
  auto rows = read_index(index_);
  std::optional<Checkpoint> best;
  const hsize_t cols = std::max<std::size_t>(1, state_bytes());
  for (int slot = 0; slot < kSlots; ++slot) {
    const long long* f = &rows[slot * kFields];
    if (f[0] < 0 || f[1] > frames_available || (best && best->frame >= f[0])) continue;
    Checkpoint c{f[0], f[1], f[2], f[3], f[4], {}, {}, {}};
    std::vector<std::byte> bytes(cols);
    H5Handle space = row_space(state_, slot, cols);
    const hsize_t count[2] = {1, cols};
    H5Handle mem = h5_check(H5Screate_simple(2, count, nullptr), H5Sclose, "checkpoint memory");
    if (H5Dread(state_, H5T_NATIVE_UCHAR, mem, space, H5P_DEFAULT, bytes.data()) < 0) continue;
    c.positions.assign(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(position_bytes_));
    c.velocities.assign(bytes.begin() + static_cast<std::ptrdiff_t>(position_bytes_),
                        bytes.begin() + static_cast<std::ptrdiff_t>(position_bytes_ + velocity_bytes_));
    c.carried.assign(bytes.begin() + static_cast<std::ptrdiff_t>(position_bytes_ + velocity_bytes_),
                     bytes.begin() + static_cast<std::ptrdiff_t>(state_bytes()));
    std::uint64_t stored = 0;
    std::memcpy(&stored, &f[5], sizeof stored);
    if (hash_of(c) == stored || hash_of(c, fnv1a) == stored) {
      best = std::move(c);
      if (slot_found != nullptr) *slot_found = slot;
    }
  }
  return best;
}

std::optional<Checkpoint> CheckpointSlots::take_newest(long long frames_available) {
  int best_slot = -1;
  std::optional<Checkpoint> best = newest(frames_available, &best_slot);
  if (!best) return best;
  auto rows = read_index(index_);
  for (int slot = 0; slot < kSlots; ++slot) {
    if (slot != best_slot) rows[slot * kFields] = -1;
  }
  h5_check(H5Dwrite(index_, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()), "writing /checkpoint/index");
  next_slot_ = 1 - best_slot;
  return best;
}

}  // namespace atssim::io
