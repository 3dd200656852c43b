#pragma once
// NvCloth's TripletScheduler (seed 002): orders triangles ("triplets") so
// that the ones processed together share no particle.
//   simd(width) (graph/simd_batches, any arity): greedy batches of `width` triplets sharing no particle;
//     a set is a run of triplets split into such batches, a new set starts
//     when no remaining triplet fits the current batch; each set is padded
//     to a multiple of `width` with a dummy triplet (n, n + 1, n + 2) of
//     particles past the last one (NvCloth's paddingDummy).
//   warp(width): sets of triplets sharing no particle (at least as many as
//     the most triplets one particle has), each triplet put in the set where
//     it adds the fewest shared-memory bank replays (bank = particle index
//     mod width; a warp of `width` consecutive triplets of a set reads each
//     of its three particle slots in one instruction, replayed once per extra
//     access to the busiest bank).
#include <array>
#include <span>
#include <vector>

namespace atssim::graph {

using Triplet = std::array<int, 3>;

struct SimdBatches {
  std::vector<Triplet> triplets;  // the input reordered, sets one after another
  std::vector<int> set_sizes;     // triplets per set (before padding)
  std::vector<Triplet> padded;    // each set padded to a multiple of width with the dummy
};

struct WarpSets {
  std::vector<Triplet> triplets;  // the input reordered, sets one after another (insertion order inside a set)
  std::vector<int> set_sizes;
  long long replays = 0;  // instruction executions over every warp of every set (see bank_replays)
};

SimdBatches schedule_simd(std::span<const Triplet> triplets, int particle_count, int width);
WarpSets schedule_warp(std::span<const Triplet> triplets, int particle_count, int width);

// Executions of the three particle reads over every warp (each `width`
// consecutive triplets of a set, the last one possibly shorter): per warp
// and slot, the largest number of triplets whose particle falls in one bank.
long long bank_replays(std::span<const Triplet> triplets, std::span<const int> set_sizes, int width);

}  // namespace atssim::graph
