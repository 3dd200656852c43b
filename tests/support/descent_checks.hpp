#pragma once
// The descent checks that `atssim converge` traces of VBD, SOSD and JPGD
// share: never below the Newton minimum, and y falling with every doubling
// of the iterations, except JPGD's first Chebyshev-accelerated step, which
// overshoots (omega_2 > 1, Wang 2015).
#include <catch2/catch.hpp>

#include <cmath>

#include "io/convergence_writer.hpp"

namespace atssim::test {

inline void check_descends(const io::ConvergenceResult& r, const io::ConvergenceTrace& t) {
  INFO(t.variant);
  for (std::size_t i = 0; i < t.energy.size(); ++i) {
    CHECK(t.energy[i] >= r.energy_reference);  // not below the minimum
    const bool chebyshev_start = t.variant.rfind("jpgd", 0) == 0 && i == 1;
    if (i > 0 && !chebyshev_start) CHECK(t.relative_error[i] < t.relative_error[i - 1]);
  }
}

// The weaker check of scenes with contact: every trace stays above the
// Newton minimum (to 1e-9 of it) and ends with a smaller y than it starts
// (between doublings it may rise). Also that Newton converged, three
// traces, and the run starts above the minimum.
inline void check_ends_lower(const io::ConvergenceResult& r) {
  REQUIRE(r.newton_status == "converged");
  REQUIRE(r.traces.size() == 3);
  CHECK(r.energy_start > r.energy_reference);
  for (const auto& t : r.traces) {
    INFO(t.variant << ": y = " << t.relative_error.front() << " … " << t.relative_error.back());
    for (double e : t.energy) CHECK(e >= r.energy_reference - 1e-9 * std::abs(r.energy_reference));
    CHECK(t.relative_error.back() < t.relative_error.front());
  }
}

}  // namespace atssim::test
