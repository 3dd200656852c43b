#pragma once
// solver.ordering: color_batches on the host, for bench_native --ordering
// color_batches (docs/benchmarks.md, "Native loops"): each color block of
// the layout's stretch, bending and tet sets cut into consecutive groups of 8, the
// last group of a block padded with dummies, a group run as 8 float lanes
// (bench/float8_lanes.hpp, kernels/xpbd/xpbd.cl's *_lanes). The groups of a
// block share no particle, so threads > 1 runs each block as a
// tbb::parallel_for over its groups, as bench/plain_xpbd.hpp does over its
// elements; the updates come in the color loop's order, so only the lanes'
// float rounding could set the two apart. The padded arrays are built here,
// apart from the library's (solver/xpbd/xpbd_batches), as a sceptic would.
#include <vector>

#include "float8_lanes.hpp"
#include "plain_xpbd.hpp"

namespace atssim::bench {

class PlainXpbdColorBatches : public PlainParticles {
 public:
  PlainXpbdColorBatches(const solver::SimLayout& layout, double h, int iterations, bool parallel)
      : PlainParticles(layout, h),
        n_(static_cast<int>(layout.x.size())),
        stretch_(cut_blocks(layout.stretch, layout.stretch_blocks, ats_distance_c{n_, n_, 0.0f, 0.0f, 0.0f})),
        bend_(cut_blocks(layout.bend, layout.bend_blocks, bend_dummy(n_))),
        tet_(cut_blocks(layout.tets, layout.tet_blocks, tet_dummy(n_))),
        stretch_lambda_(stretch_.elements.size()),
        bend_lambda_(bend_.elements.size() * 3),
        tet_lambda_(tet_.elements.size() * ATS_TET_LAMBDA_STRIDE),
        iterations_(iterations),
        parallel_(parallel),
        inertia_dt_(static_cast<float>(solver::inertia_dt(layout, h))),
        inv_h_(solver::has_spring_damping(layout) ? 1.0f / static_cast<float>(h) : 0.0f) {
    for (const ats_tet_c& t : layout.tets) {
      if (t.model != ATS_TET_STVK) throw input_error("bench_native --ordering color_batches: StVK tets only (XPBD's)");
    }
  }

  void substep() {
    predict(parallel_);
    for (int it = 0; it < iterations_; ++it) {
      const bool reset = it == 0;
      for (std::size_t b = 0; b + 1 < stretch_.groups.size(); ++b)
        stretch(stretch_.groups[b], stretch_.groups[b + 1], reset);
      for (std::size_t b = 0; b + 1 < bend_.groups.size(); ++b) bend(bend_.groups[b], bend_.groups[b + 1], reset);
      for (std::size_t b = 0; b + 1 < tet_.groups.size(); ++b) tet(tet_.groups[b], tet_.groups[b + 1], reset);
      ground(parallel_);
    }
    update_velocity(parallel_);
  }

 private:
  // A set with each block padded to whole groups of 8.
  template <class Element>
  struct Groups {
    std::vector<Element> elements;  // 8 * groups.back()
    std::vector<int> groups;        // group offsets of the blocks, one more than the blocks
  };

  template <class Element>
  static Groups<Element> cut_blocks(const std::vector<Element>& set, const std::vector<int>& blocks,
                                    const Element& dummy) {
    Groups<Element> out;
    out.groups.push_back(0);
    for (std::size_t b = 0; b + 1 < blocks.size(); ++b) {
      out.elements.insert(out.elements.end(), set.begin() + blocks[b], set.begin() + blocks[b + 1]);
      out.elements.resize((out.elements.size() + 7) / 8 * 8, dummy);
      out.groups.push_back(static_cast<int>(out.elements.size() / 8));
    }
    return out;
  }
  static ats_bend_c bend_dummy(int n) {
    ats_bend_c c{};
    for (int& v : c.v) v = n;
    c.model = ATS_BEND_ISOMETRIC;  // a dihedral dummy would send its group down the scalar path
    return c;
  }
  static ats_tet_c tet_dummy(int n) {
    ats_tet_c c{};
    for (int& v : c.v) v = n;
    return c;
  }

  void stretch(int first, int last, bool reset) {
    solver::Float4* x = x_.data();
    const solver::Float4* x0 = x_prev_.data();
    const ats_distance_c* con = stretch_.elements.data();
    float* lambda = stretch_lambda_.data();
    const int n = n_;
    const float dt = inertia_dt_, inv_h = inv_h_;
    plain_range(parallel_, first, last,
                [=](int g) { lanes::stretch_group8(x, x0, con + 8 * g, lambda + 8 * g, n, dt, inv_h, reset); });
  }

  void bend(int first, int last, bool reset) {
    solver::Float4* x = x_.data();
    const ats_bend_c* con = bend_.elements.data();
    float* lambda = bend_lambda_.data();
    const int n = n_;
    const float dt = inertia_dt_;
    plain_range(parallel_, first, last,
                [=](int g) { lanes::bend_group8(x, con + 8 * g, lambda + 24 * g, n, dt, reset); });
  }

  void tet(int first, int last, bool reset) {
    solver::Float4* x = x_.data();
    const ats_tet_c* con = tet_.elements.data();
    float* lambda = tet_lambda_.data();
    const int n = n_;
    const float dt = inertia_dt_;
    plain_range(parallel_, first, last, [=](int g) {
      lanes::tet_group8(x, con + 8 * g, lambda + 8 * ATS_TET_LAMBDA_STRIDE * g, n, dt, reset);
    });
  }

  int n_;
  Groups<ats_distance_c> stretch_;
  Groups<ats_bend_c> bend_;
  Groups<ats_tet_c> tet_;
  std::vector<float> stretch_lambda_, bend_lambda_, tet_lambda_;
  int iterations_;
  bool parallel_;
  float inertia_dt_, inv_h_;
};

}  // namespace atssim::bench
