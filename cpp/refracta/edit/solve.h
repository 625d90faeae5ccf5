// solve_edit: find the parameters of a field that make each pair's light path pass through its
// source. Chooses the back-end, holds parameters no pair depends on fixed (reported), measures
// the result.
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/edit/edit_settings.h"

namespace refracta {

// control.cancel stops the solve (throws Cancelled); control.done / total report iterations.
SolveSummary solve_edit(const FieldPtr& field, const std::vector<PointPair>& pairs,
                        const ProblemSpec& spec, const SolveSettings& settings, WorkControl& control);

}  // namespace refracta
