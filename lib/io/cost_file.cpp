#include "io/cost_file.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}

bool parse_ms(const std::string& text, double& value) {
  if (text == "inf") {
    value = sched::kCannotRun;
    return true;
  }
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    return used == text.size() && value >= 0.0;
  } catch (...) {
    return false;
  }
}

}  // namespace

std::size_t cost_file_devices(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw input_error(fmt::format("{}: cost file cannot be read; check the path", path));
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto cells = split_csv(line);
    if (cells[0] == "task" || cells[0] == "latency_ms") continue;
    return cells.size() - 1;
  }
  throw input_error(fmt::format("{}: the cost file lists no task", path));
}

CostFile read_cost_file(const std::string& path, const sched::TaskGraph& graph) {
  std::ifstream in(path);
  if (!in) throw input_error(fmt::format("{}: cost file cannot be read; check the path", path));
  std::unordered_map<std::string, sched::TaskId> by_name;
  for (sched::TaskId t = 0; t < graph.size(); ++t) by_name[graph.task(t).name] = t;

  CostFile file;
  std::vector<std::vector<double>> rows(graph.size());
  std::vector<char> seen(graph.size(), 0);
  std::size_t devices = 0;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const auto cells = split_csv(line);
    if (cells[0] == "task") continue;  // header
    if (cells[0] == "latency_ms") {
      if (cells.size() != 2 || !parse_ms(cells[1], file.latency_ms) || !(file.latency_ms < sched::kCannotRun)) {
        throw input_error(fmt::format("{}:{}: expected 'latency_ms,<ms ≥ 0>' (a finite number)", path, line_no));
      }
      continue;
    }
    const auto it = by_name.find(cells[0]);
    if (it == by_name.end()) {
      throw input_error(
          fmt::format("{}:{}: task '{}' is not in this substep's task graph; write the costs for the "
                      "same scene, method and schedule (atssim schedule --csv writes them)",
                      path, line_no, cells[0]));
    }
    if (cells.size() < 2) throw input_error(fmt::format("{}:{}: task '{}' has no cost", path, line_no, cells[0]));
    if (devices == 0) devices = cells.size() - 1;
    if (cells.size() - 1 != devices) {
      throw input_error(
          fmt::format("{}:{}: {} costs, but earlier lines have {}; give one cost per device on every "
                      "line",
                      path, line_no, cells.size() - 1, devices));
    }
    std::vector<double> row(devices);
    for (std::size_t d = 0; d < devices; ++d) {
      if (!parse_ms(cells[d + 1], row[d])) {
        throw input_error(
            fmt::format("{}:{}: '{}' is not a cost in ms (a number ≥ 0, or inf)", path, line_no, cells[d + 1]));
      }
    }
    // The scheduler takes every table it is given as sound (sched/input_checks):
    // what a file can get wrong is refused here, at its line.
    if (std::none_of(row.begin(), row.end(), [](double ms) { return ms < sched::kCannotRun; })) {
      throw input_error(
          fmt::format("{}:{}: task '{}' costs inf on every device, so no device can run it; give a "
                      "cost in ms for at least one",
                      path, line_no, cells[0]));
    }
    rows[it->second] = std::move(row);
    seen[it->second] = 1;
  }
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    if (!seen[t]) {
      throw input_error(fmt::format("{}: no cost for task '{}' ({} of {} tasks given); list every task", path,
                                    graph.task(t).name, std::count(seen.begin(), seen.end(), 1), graph.size()));
    }
  }
  file.costs = sched::CostTable::from_rows(rows);
  return file;
}

std::string format_cost_file(const sched::TaskGraph& graph, const sched::CostTable& costs, double latency_ms) {
  std::string out = "# atssim cost table: ms per task and device\n";
  out += fmt::format("latency_ms,{:.6g}\ntask", latency_ms);
  for (std::size_t d = 0; d < costs.devices; ++d) out += fmt::format(",dev{}_ms", d);
  out += "\n";
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    out += graph.task(t).name;
    for (std::size_t d = 0; d < costs.devices; ++d) out += fmt::format(",{:.6g}", costs.at(t, d));
    out += "\n";
  }
  return out;
}

}  // namespace atssim::io
