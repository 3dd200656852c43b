#pragma once
// Every file the scene stage reads is checked before it is read: it exists,
// is a regular file (not a folder, a FIFO or /dev/zero, which would be read
// until memory runs out) and is not absurdly large.
#include <cstdint>
#include <string>
#include <string_view>

namespace atssim::scene {

constexpr std::uintmax_t kMaxSceneBytes = 64ull << 20;  // a scene is text: 64 MiB is far beyond any real one
constexpr std::uintmax_t kMaxMeshBytes = 8ull << 30;

// Throws atssim::Error (input): "<where>: <kind> '<path>' <what is wrong>; <fix>"
// (where = "" names only the path).
void check_input_file(const std::string& path, std::string_view kind, std::string_view where, std::uintmax_t max_bytes);

}  // namespace atssim::scene
