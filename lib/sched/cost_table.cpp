#include "sched/cost_table.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

CostTable::CostTable(std::size_t task_count, std::size_t device_count, double fill)
    : tasks(task_count), devices(device_count), ms(task_count * device_count, fill) {}

CostTable CostTable::from_rows(const std::vector<std::vector<double>>& rows) {
  const std::size_t width = rows.empty() ? 0 : rows.front().size();
  CostTable table(rows.size(), width);
  for (std::size_t t = 0; t < rows.size(); ++t) {
    if (rows[t].size() != width) {
      throw internal_error(fmt::format("cost table: row {} has {} devices, row 0 has {}", t, rows[t].size(), width));
    }
    std::copy(rows[t].begin(), rows[t].end(), table.ms.begin() + t * width);
  }
  return table;
}

void CostTable::add_device(double fill) {
  std::vector<double> wider(tasks * (devices + 1), fill);
  for (std::size_t t = 0; t < tasks; ++t) {
    std::copy_n(ms.begin() + t * devices, devices, wider.begin() + t * (devices + 1));
  }
  ms = std::move(wider);
  ++devices;
}

double mean_cost(const CostTable& costs, TaskId task) {
  double sum = 0.0;
  int finite = 0;
  for (double c : costs.row(task)) {
    if (c < kCannotRun) {
      sum += c;
      ++finite;
    }
  }
  return finite > 0 ? sum / finite : kCannotRun;
}

double min_cost(const CostTable& costs, TaskId task) {
  const auto row = costs.row(task);
  return row.empty() ? kCannotRun : *std::min_element(row.begin(), row.end());
}

}  // namespace atssim::sched
