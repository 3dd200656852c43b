#pragma once
// What a task of a substep plan does, as a kind with traits, so that the plan
// transforms, the scheduler's callers and the output ask a trait instead of
// comparing names (DESIGN.md "plan/": task kinds with traits). A kind is
// declared once, as a constant, by the code that makes its tasks: the kinds
// every method shares below, a method's own in its folder (e.g.
// solver/xpbd/xpbd_plan.hpp), so that a new method adds kinds without
// touching this file. sched::Task::kind holds the kind's label.
#include <cstdint>
#include <string>
#include <string_view>

#include "sched/task_graph.hpp"

namespace atssim::plan {

struct KindTraits {
  std::string_view name;  // unique among the kinds: "stretch"
  // Its blocks form a Gauss-Seidel chain: each reads what the one before
  // wrote. Async Gauss-Seidel keeps the order of such a kind across
  // iterations and ranks it by sched::gauss_seidel_rank (paper §4.1.2).
  bool gauss_seidel = false;
  // Async Gauss-Seidel serializes it at the end of its iteration (paper
  // §4.2.1, "Asyn-Serial Collision").
  bool serial = false;
  // Its launches range over particles (not elements): what it reads and
  // writes is the particle range itself.
  bool per_particle = false;
};

class TaskKind {
 public:
  constexpr explicit TaskKind(KindTraits traits) : traits_(traits) {}

  constexpr const KindTraits& traits() const { return traits_; }
  constexpr std::string_view name() const { return traits_.name; }
  // The label of its tasks in a sched::TaskGraph: a hash of the name (FNV-1a,
  // 31 bits), the same in every build; never sched::kMixedKind.
  constexpr int label() const {
    std::uint32_t h = 2166136261u;
    for (char c : traits_.name) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
    return static_cast<int>(h & 0x7fffffffu);
  }
  // Kinds are named uniquely (make_task refuses two kinds of one label).
  friend constexpr bool operator==(const TaskKind& a, const TaskKind& b) { return a.name() == b.name(); }

  // The kinds of the steps every method shares, and of the plan transforms.
  static const TaskKind predict;          // x_t kept, x~ = x_t + h v + h² g: before the iterations
  static const TaskKind jacobi;           // every particle from the same iterate (JPGD, explicit stages)
  static const TaskKind collision;        // contact handling at the end of an iteration
  static const TaskKind copy;             // the result moved into the positions
  static const TaskKind update_velocity;  // v = (x − x_t) / h: after the iterations
  static const TaskKind publish;          // async: a device's positions snapshot for others
  static const TaskKind merge;            // async: another device's snapshot merged into this one's copy
  static const TaskKind energy;           // per-element terms of the incremental potential
  static const TaskKind friction;         // Coulomb friction of the colliders: after the iterations
  static const TaskKind detection;        // contact detection between simulated surfaces: before the iterations

 private:
  KindTraits traits_;
};

inline constexpr TaskKind TaskKind::predict{{"predict", false, false, true}};
inline constexpr TaskKind TaskKind::jacobi{{"jacobi", false, false, true}};
inline constexpr TaskKind TaskKind::collision{{"collision", false, true, true}};
inline constexpr TaskKind TaskKind::copy{{"copy", false, false, true}};
inline constexpr TaskKind TaskKind::update_velocity{{"update_velocity", false, false, true}};
inline constexpr TaskKind TaskKind::publish{{"publish", false, false, true}};
inline constexpr TaskKind TaskKind::merge{{"merge", false, false, true}};
inline constexpr TaskKind TaskKind::energy{{"energy", false, false, false}};
inline constexpr TaskKind TaskKind::friction{{"friction", false, false, true}};
inline constexpr TaskKind TaskKind::detection{{"detection", false, false, false}};

inline KindTraits traits(const TaskKind& kind) { return kind.traits(); }
inline std::string_view to_string(const TaskKind& kind) { return kind.name(); }

// A task of a plan: its label is the kind's. The kind becomes known to
// kind_of(); throws atssim::Error (internal) when another kind has its name or
// its label.
sched::Task make_task(std::string name, const TaskKind& kind, int iteration = -1, int block = -1);

// The kind of a task of a plan's graph (by its label); throws atssim::Error
// (internal) for a label of no kind a task was made with (a merged task, or a
// graph from elsewhere).
TaskKind kind_of(const sched::Task& task);

}  // namespace atssim::plan
