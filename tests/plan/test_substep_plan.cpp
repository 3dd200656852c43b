#include <catch2/catch.hpp>

#include "plan/substep_plan.hpp"
#include "util/error.hpp"

using namespace atssim;
using plan::BufferRole;
using plan::TaskKind;

namespace {

// A kind declared outside plan/, as a method declares its own.
constexpr TaskKind kSweep{{"test_sweep", true, false, true}};

}  // namespace

TEST_CASE("a task's kind survives the scheduler's label and has its traits") {
  const sched::Task t = plan::make_task("it1/sweep/c0", kSweep, 0, 0);
  CHECK(plan::kind_of(t) == kSweep);
  CHECK(plan::kind_of(t).traits().per_particle);
  CHECK(plan::to_string(kSweep) == "test_sweep");
  CHECK(plan::traits(kSweep).gauss_seidel);
  const sched::Task c = plan::make_task("it1/collision", TaskKind::collision, 0);
  CHECK(plan::kind_of(c) == TaskKind::collision);
  CHECK(plan::traits(TaskKind::collision).serial);
  CHECK_FALSE(plan::traits(TaskKind::jacobi).gauss_seidel);
  CHECK(plan::traits(TaskKind::predict).per_particle);
  CHECK_FALSE(plan::traits(TaskKind::energy).per_particle);
}

TEST_CASE("a kind's label is a hash of its name: FNV-1a, 31 bits") {
  // FNV-1a of "a": (2166136261 ^ 97) * 16777619 mod 2^32 = 0xe40c292c.
  CHECK(TaskKind({"a"}).label() == static_cast<int>(0xe40c292cu & 0x7fffffffu));
  CHECK(TaskKind({"stretch"}).label() != TaskKind({"bend"}).label());
}

TEST_CASE("a label that is no task kind is an error naming the task") {
  sched::Task merged{"a+b", sched::kMixedKind, 0, -1};
  CHECK_THROWS_WITH(plan::kind_of(merged), Catch::Contains("a+b"));
  sched::Task foreign{"x", 999, 0, -1};
  CHECK_THROWS_AS(plan::kind_of(foreign), Error);
}

TEST_CASE("two kinds of one name and other traits are a bug") {
  (void)plan::make_task("t", kSweep);
  const TaskKind other{{"test_sweep", false, false, true}};
  CHECK_THROWS_WITH(plan::make_task("u", other), Catch::Contains("'test_sweep'") && Catch::Contains("other traits"));
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
