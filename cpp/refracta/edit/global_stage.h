// The global stage of an edit's default strategy (solve.cpp): a design of points over the free
// parameters' box whose costs are evaluated in parallel, so that local solves start from the best
// of them instead of from wherever the user's field happened to be. The design has
//  - a scan along each free parameter's axis through the start: an artist who moves an image
//    usually asks one layer (a height, a strength) to move far, past cost barriers a local solver
//    cannot cross (the logistic inversion's h_ciso: issue 11);
//  - quasi-random points (core/low_discrepancy.h) over the whole box and near the start.
#pragma once

#include "refracta/edit/edit_settings.h"

#include <string>
#include <vector>

namespace refracta {

struct DesignPoint {
  std::vector<double> x;  // free values
  double cost = 0.0;      // 1/2 sum of squared residuals [m^2]; +inf where a pair cannot be traced
  std::string label;      // where it comes from, for the stage report
  // Per pair, the vertical component of its weighted residual (> 0: the path passes above the
  // source); empty where the cost is +inf.
  std::vector<double> vertical;
};

struct Design {
  std::vector<DesignPoint> points;  // sorted by cost, lowest first (points left out: +inf)
  int64_t evaluated = 0;            // points whose cost was evaluated
  StopReason stopped = StopReason::kNone;  // the budget's limit that cut the design short
};

// per_param scan points on each free parameter's axis (cell midpoints of its unit range,
// EditProblem::to_unit), refined around each axis's lowest local minima, and per_param * m
// quasi-random points, half over the unit box and half within a tenth of it of the start;
// their costs, every point on its own thread (pairs in turn: each thread builds a model once per
// point). Each point spends one evaluation of the budget; once its evaluations or time are used
// up the remaining points are left out. Cancelling throws Cancelled.
Design evaluate_design(const EditProblem& problem, int per_param, SolveBudget& budget);

// Up to `count` points of a cost-sorted list, lowest cost first, each at least `spacing` (the
// largest coordinate difference in the unit box of the bounds) from the ones taken before, and
// none with an infinite cost.
std::vector<DesignPoint> spread_best(const EditProblem& problem, const std::vector<DesignPoint>& sorted, int count,
                                     double spacing);

}  // namespace refracta
