#include "plan/split_plan.hpp"

#include <cmath>
#include <numeric>
#include <string_view>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

namespace {

// Element ranges [begin, end) of each part of `count` elements.
std::vector<std::pair<std::int32_t, std::int32_t>> part_ranges(std::int32_t count, std::span<const double> fractions,
                                                               std::size_t granule) {
  std::vector<std::pair<std::int32_t, std::int32_t>> ranges;
  double cumulative = 0.0;
  std::int32_t begin = 0;
  for (std::size_t p = 0; p < fractions.size(); ++p) {
    cumulative += fractions[p];
    std::int32_t end = count;
    if (p + 1 < fractions.size()) {
      const double exact = cumulative * count;
      const auto g = static_cast<double>(granule);
      end = static_cast<std::int32_t>(std::min<double>(count, std::round(exact / g) * g));
      end = std::max(end, begin);
    }
    ranges.emplace_back(begin, end);
    begin = end;
  }
  return ranges;
}

void check_fractions(std::span<const double> fractions) {
  const double total = std::accumulate(fractions.begin(), fractions.end(), 0.0);
  if (fractions.empty() || std::abs(total - 1.0) > 1e-9) {
    throw internal_error(
        fmt::format("split_plan: {} fractions summing to {} (must sum to 1)", fractions.size(), total));
  }
}

}  // namespace

std::vector<double> recut_plan(SubstepPlan& plan, std::span<const double> fractions, std::size_t granule) {
  check_fractions(fractions);
  const std::size_t n = fractions.size();
  std::vector<double> share(plan.graph.size(), 1.0);
  // split_plan adds the parts of one task as consecutive ids 0 … n−1, named
  // "<task>#<part>".
  const auto base = [&](sched::TaskId t) {
    const std::string& name = plan.graph.task(t).name;
    return std::string_view(name).substr(0, name.rfind('#'));
  };
  for (sched::TaskId t = 0; t + n <= plan.graph.size(); ++t) {
    bool whole_group = true;
    for (std::size_t p = 0; p < n && whole_group; ++p) {
      whole_group = plan.graph.task(t + p).part == static_cast<int>(p) && base(t + p) == base(t) &&
                    plan.launches[t + p].size() == 1;
    }
    if (!whole_group) continue;
    const std::int32_t first = plan.launches[t][0].range.first;
    const Range& last = plan.launches[t + n - 1][0].range;
    const std::int32_t count = last.first + last.count - first;
    const auto ranges = part_ranges(count, fractions, granule);
    for (std::size_t p = 0; p < n; ++p) {
      plan.launches[t + p][0].range = {first + ranges[p].first, ranges[p].second - ranges[p].first};
      share[t + p] = count > 0 ? static_cast<double>(ranges[p].second - ranges[p].first) / count : 0.0;
    }
    t += n - 1;
  }
  return share;
}

std::size_t part_granule(std::size_t work_group_elements) { return work_group_elements > 0 ? work_group_elements : 8; }

SubstepPlan split_plan(const SubstepPlan& plan, std::span<const double> fractions, std::size_t granule) {
  check_fractions(fractions);
  SubstepPlan out;
  out.program = plan.program;
  out.buffers = plan.buffers;
  out.particle_count = plan.particle_count;

  // parts[t]: the new task ids that together perform old task t.
  std::vector<std::vector<sched::TaskId>> parts(plan.graph.size());
  for (sched::TaskId t : plan.graph.topological_order()) {
    const sched::Task& task = plan.graph.task(t);
    const auto& launches = plan.launches[t];
    const bool splittable = fractions.size() > 1 && launches.size() == 1;
    if (!splittable) {
      parts[t].push_back(out.add_task(task, launches));
    } else {
      const KernelLaunch& whole = launches[0];
      const auto ranges = part_ranges(whole.range.count, fractions, granule);
      // Every part is kept, an empty one too (it runs nothing), so that each
      // split task has one part per fraction and recut_plan can move the cut.
      for (std::size_t p = 0; p < ranges.size(); ++p) {
        const auto [b, e] = ranges[p];
        KernelLaunch piece = whole;
        piece.range = {whole.range.first + b, e - b};
        sched::Task named = task;
        named.name = fmt::format("{}#{}", task.name, p);
        named.part = static_cast<int>(p);
        parts[t].push_back(out.add_task(std::move(named), {std::move(piece)}));
      }
    }
    for (const sched::Edge& edge : plan.graph.predecessors(t)) {
      for (sched::TaskId from : parts[edge.from]) {
        for (sched::TaskId to : parts[t]) out.graph.add_edge(from, to, edge.comm);
      }
    }
  }
  return out;
}

}  // namespace atssim::plan
