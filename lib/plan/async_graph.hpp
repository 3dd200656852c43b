#pragma once
// The task graph of asynchronous Gauss-Seidel (He et al. 2025 §4.2.1): the
// serial Gauss-Seidel order is relaxed so that iterations overlap.
//   - each kind keeps its own order (stretch blocks of every iteration in
//     sequence, bending blocks likewise): "the execution order of the same
//     task type across iterations must be maintained";
//   - a task of iteration k waits for all of iteration k − depth: at most
//     `depth` iterations are in flight ("n-iteration concurrency");
//   - tasks outside the iterations (predict, update velocity) keep their
//     place: before, respectively after, every iteration task.
//   - serial kinds (KindTraits::serial: collision) are serialized at the end
//     of their iteration (§4.2.1, "Asyn-Serial Collision"): they wait for
//     every task of the iteration and the next iteration waits for them;
// depth 1 means no overlap at all: the graph stays the serial chain, so
// async with depth 1 is serial Gauss-Seidel.
#include "plan/substep_plan.hpp"

namespace atssim::plan {

// The same tasks and launches as `serial` (a Gauss-Seidel chain as the
// solvers emit it), with the relaxed edges. Throws atssim::Error for depth < 1.
SubstepPlan async_graph(const SubstepPlan& serial, int depth);

}  // namespace atssim::plan
