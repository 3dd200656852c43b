#pragma once
// The descent checks that `atssim converge` traces of VBD, SOSD and JPGD
// share: never below the Newton minimum, and y falling with every doubling
// of the iterations, except JPGD's first Chebyshev-accelerated step, which
// overshoots (omega_2 > 1, Wang 2015).
#include <catch2/catch.hpp>

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

}  // namespace atssim::test
