#pragma once
// Published reference problems, typed in from the papers.
#include <string>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched::test {

struct Problem {
  TaskGraph graph;
  CostTable costs;
  DeviceLinks links;
};

struct WeightedEdge {
  TaskId from;
  TaskId to;
  double weight;
};

inline Problem make_problem(const std::vector<std::string>& names, const std::vector<std::vector<double>>& cost_rows,
                            const std::vector<WeightedEdge>& edges) {
  Problem p;
  for (const auto& name : names) p.graph.add_task({name, 0, -1, -1});
  for (const auto& e : edges) p.graph.add_edge(e.from, e.to, e.weight);
  p.costs = CostTable::from_rows(cost_rows);
  p.links = DeviceLinks::weighted(p.costs.devices);  // cross-device comm = edge weight
  return p;
}

// Topcuoglu, Hariri & Wu 2002, Fig. 2 (10 tasks, 3 processors). Task ids
// are the paper's n1..n10 minus one.
// clang-format off
inline Problem topcuoglu_2002() {
  return make_problem({"n1", "n2", "n3", "n4", "n5", "n6", "n7", "n8", "n9", "n10"},
                      {{14, 16, 9},
                       {13, 19, 18},
                       {11, 13, 19},
                       {13, 8, 17},
                       {12, 13, 10},
                       {13, 16, 9},
                       {7, 15, 11},
                       {5, 11, 14},
                       {18, 12, 20},
                       {21, 7, 16}},
                      {{0, 1, 18}, {0, 2, 12}, {0, 3, 9}, {0, 4, 11}, {0, 5, 14},
                       {1, 7, 19}, {1, 8, 16}, {2, 6, 23}, {3, 7, 27}, {3, 8, 23},
                       {4, 8, 13}, {5, 7, 15}, {6, 9, 17}, {7, 9, 11}, {8, 9, 13}});
}

// Arabnejad & Barbosa 2014 (PEFT), sample DAG (10 tasks, 3 processors).
// Task ids are the paper's T1..T10 minus one.
inline Problem arabnejad_2014() {
  return make_problem({"T1", "T2", "T3", "T4", "T5", "T6", "T7", "T8", "T9", "T10"},
                      {{22, 21, 36},
                       {22, 18, 18},
                       {32, 27, 43},
                       {7, 10, 4},
                       {29, 27, 35},
                       {26, 17, 24},
                       {14, 25, 30},
                       {29, 23, 36},
                       {15, 21, 8},
                       {13, 16, 33}},
                      {{0, 1, 17}, {0, 2, 31}, {0, 3, 29}, {0, 4, 13}, {0, 5, 7},
                       {1, 7, 3}, {1, 8, 30}, {2, 6, 16}, {3, 7, 11}, {3, 8, 7},
                       {4, 8, 57}, {5, 7, 5}, {6, 9, 9}, {7, 9, 42}, {8, 9, 7}});
}

// clang-format on

}  // namespace atssim::sched::test
