#include <catch2/catch.hpp>

#include "plan/element_sets.hpp"
#include "plan/transfer_plan.hpp"

using namespace atssim;
using plan::ElementSet;
using plan::ElementSets;
using plan::ExecutionStep;

namespace {

ElementSets writes(plan::BufferId buffer, std::vector<std::int32_t> indices, std::uint32_t bytes = 16) {
  ElementSets s;
  s.add(ElementSet{buffer, bytes, std::move(indices)});
  return s;
}

std::vector<std::int32_t> indices_of(const plan::Transfer& t, plan::BufferId buffer) {
  for (const ElementSet& s : t.elements.sets()) {
    if (s.buffer == buffer) return s.indices;
  }
  return {};
}

}  // namespace

TEST_CASE("element sets unite exactly, in words when element sizes differ") {
  ElementSets a;
  a.add(ElementSet{0, 16, {1, 2, 7}});
  a.add(ElementSet{0, 16, {2, 3}});
  a.add(ElementSet{1, 4, {0}});
  REQUIRE(a.sets().size() == 2);
  CHECK(a.sets()[0].indices == std::vector<std::int32_t>{1, 2, 3, 7});
  CHECK(a.bytes() == 4 * 16 + 4);
  a.add(ElementSet{0, 4, {0, 30}});  // words 0 and 30: element 7 is words 28..31
  CHECK(a.sets()[0].element_bytes == 4);
  CHECK(a.sets()[0].indices == std::vector<std::int32_t>{0, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 28, 29, 30, 31});
  CHECK_FALSE(a.sets()[0].contiguous());
  CHECK(ElementSet{0, 4, {3, 4, 5}}.contiguous());
}

TEST_CASE("a launch writes its declared spans over its range, and writable arguments it does not declare whole") {
  plan::KernelLaunch l{
      "f", {2, 3}, {plan::KernelArg::of_buffer(0), plan::KernelArg::of_buffer(1), plan::KernelArg::of_buffer(2)}, {}};
  const auto table =
      std::make_shared<const std::vector<std::int32_t>>(std::vector<std::int32_t>{0, 1, 1, 2, 9, 3, 3, 4, 5, 6});
  l.writes = {plan::WriteSpan::per_index(0, 16, 2, table), plan::WriteSpan::per_element(1, 4, 10)};
  const std::vector<std::size_t> sizes{160, 64, 8};
  const std::vector<char> writable{1, 1, 1};
  const ElementSets w = plan::written_elements(l, writable, sizes);
  REQUIRE(w.sets().size() == 3);
  // elements 2, 3, 4 of the table, two entries each: (9, 3), (3, 4), (5, 6)
  CHECK(w.sets()[0].indices == std::vector<std::int32_t>{3, 4, 5, 6, 9});
  CHECK(w.sets()[1].indices == std::vector<std::int32_t>{12, 13, 14});  // offset 10
  CHECK(w.sets()[2].indices == std::vector<std::int32_t>{0, 1});        // undeclared: 8 bytes, whole
  const std::vector<char> read_only{1, 1, 0};
  CHECK(plan::written_elements(l, read_only, sizes).sets().size() == 2);
}

TEST_CASE("a copy carries what the producer's device wrote up to the producer, once") {
  // Device 0: t0 writes x[0,1], t1 writes x[2]; device 1: t2 waits for t0, t3 waits for t1.
  const std::vector<ExecutionStep> steps{{0, 0, {}}, {2, 1, {0}}, {1, 0, {}}, {3, 1, {1}}};
  const std::vector<ElementSets> written{writes(0, {0, 1}), writes(0, {2}), writes(0, {5}), writes(0, {6})};
  const plan::TransferPlan p = plan::plan_transfers(steps, written, 2);
  REQUIRE(p.within.size() == 2);
  CHECK(p.within[0].from == 0);
  CHECK(p.within[0].to == 1);
  CHECK(p.within[0].before == 1);
  CHECK(indices_of(p.within[0], 0) == std::vector<std::int32_t>{0, 1});  // not t1's: it runs after t0
  CHECK(p.within[1].before == 3);
  CHECK(indices_of(p.within[1], 0) == std::vector<std::int32_t>{2});  // t0's went already
  // What device 1 wrote goes to device 0 at the boundary.
  REQUIRE(p.boundary.size() == 1);
  CHECK(p.boundary[0].from == 1);
  CHECK(p.boundary[0].to == 0);
  CHECK(p.boundary[0].producer == 3);
  CHECK(indices_of(p.boundary[0], 0) == std::vector<std::int32_t>{5, 6});
  CHECK(p.bytes_per_substep() == (2 + 1 + 2) * 16);
}

TEST_CASE("data reaches a third device through the one it waited for") {
  // t0 on device 0 writes x[0]; t1 on device 1 waits for t0 and writes x[1];
  // t2 on device 2 waits only for t1, so it must get x[0] through device 1.
  const std::vector<ExecutionStep> steps{{0, 0, {}}, {1, 1, {0}}, {2, 2, {1}}};
  const std::vector<ElementSets> written{writes(0, {0}), writes(0, {1}), ElementSets{}};
  const plan::TransferPlan p = plan::plan_transfers(steps, written, 3);
  REQUIRE(p.within.size() == 2);
  CHECK(p.within[1].from == 1);
  CHECK(p.within[1].to == 2);
  CHECK(indices_of(p.within[1], 0) == std::vector<std::int32_t>{0, 1});
}

TEST_CASE("an edge weighs the bytes its producer writes, and keeps a heavier weight it had") {
  sched::TaskGraph g;
  for (int t = 0; t < 3; ++t) g.add_task({"t" + std::to_string(t)});
  g.add_edge(0, 1);
  g.add_edge(0, 2, 1000.0);
  g.add_edge(1, 2);
  const std::vector<ElementSets> written{writes(0, {0, 1, 2}), writes(1, {4}, 4), ElementSets{}};
  plan::weigh_edges_by_writes(g, written);
  CHECK(g.successors(0)[0].comm == 48.0);    // three 16-byte particles
  CHECK(g.successors(0)[1].comm == 1000.0);  // heavier already
  CHECK(g.successors(1)[0].comm == 4.0);
  CHECK(g.predecessors(2)[1].comm == 4.0);  // both directions of the edge agree
  CHECK_THROWS_WITH(plan::weigh_edges_by_writes(g, std::vector<ElementSets>(2)), Catch::Contains("writes of 2 tasks"));
}
