#include <catch2/catch.hpp>

#include "plan/substep_plan.hpp"
#include "util/error.hpp"

using namespace atssim;
using plan::BufferRole;
using plan::TaskKind;

TEST_CASE("a task's kind survives the scheduler's label and has its traits") {
  const sched::Task t = plan::make_task("it1/stretch/c0", TaskKind::stretch, 0, 0);
  CHECK(plan::kind_of(t) == TaskKind::stretch);
  CHECK(plan::to_string(TaskKind::stretch) == "stretch");
  CHECK(plan::traits(TaskKind::stretch).gauss_seidel);
  CHECK(plan::traits(TaskKind::vertex).gauss_seidel);
  CHECK_FALSE(plan::traits(TaskKind::jacobi).gauss_seidel);
  CHECK(plan::traits(TaskKind::collision).serial);
  CHECK_FALSE(plan::traits(TaskKind::bend).serial);
  CHECK(plan::traits(TaskKind::predict).per_particle);
  CHECK_FALSE(plan::traits(TaskKind::main_block).per_particle);
}

TEST_CASE("a label that is no task kind is an error naming the task") {
  sched::Task merged{"a+b", sched::kMixedKind, 0, -1};
  CHECK_THROWS_WITH(plan::kind_of(merged), Catch::Contains("a+b"));
  sched::Task foreign{"x", 999, 0, -1};
  CHECK_THROWS_AS(plan::kind_of(foreign), Error);
}

TEST_CASE("a buffer is found by its role, and a role held twice or never is an error") {
  plan::SubstepPlan p;
  p.program = "test";
  const plan::BufferId x = p.add_buffer("x", BufferRole::positions, std::vector<std::byte>(16));
  p.add_buffer("c", BufferRole::elements, std::vector<std::byte>(16));
  p.add_buffer("d", BufferRole::elements, std::vector<std::byte>(16));
  CHECK(p.buffer(BufferRole::positions) == x);
  CHECK(p.find_buffer(BufferRole::velocities) == -1);
  CHECK_THROWS_WITH(p.buffer(BufferRole::velocities), Catch::Contains("velocities"));
  CHECK_THROWS_WITH(p.find_buffer(BufferRole::elements), Catch::Contains("'c'") && Catch::Contains("'d'"));
}

TEST_CASE("bytes_of and values_of are inverse") {
  const std::vector<float> v{1.0f, -2.5f, 3.25f};
  CHECK(plan::values_of<float>(plan::bytes_of(v)) == v);
}
