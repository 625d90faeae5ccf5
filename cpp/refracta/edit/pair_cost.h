// One residual block per point pair, as a ceres::CostFunction over the free parameters (one
// parameter block of size free.size(); 3 residuals: sqrt(weight) times the miss vector). Both
// back-ends use them: Ceres adds them to its Problem, nlopt calls Evaluate for values and
// gradients. Derivatives are automatic (ceres::Jet through the templated field and integrator)
// when the field has a templated model, central differences otherwise.
#pragma once

#include "refracta/edit/camera_rig.h"
#include "refracta/edit/evaluation_context.h"
#include "refracta/edit/point_pair.h"
#include "refracta/media/index_field.h"

#include <memory>
#include <string>
#include <vector>

namespace ceres {
class CostFunction;
}

namespace refracta {

enum class Derivatives { kAutomatic, kNumeric };
const char* derivatives_name(Derivatives derivatives);  // "automatic", "numeric"

// True when the field can be differentiated automatically.
bool has_templated_model(const IndexField& field);
// "automatic", "numeric", or "auto" (automatic when `field` has a templated model, else numeric).
Derivatives parse_derivatives(const std::string& name, const IndexField& field);

// values: every parameter of the field, then, with a camera rig, its CameraRig::kCount values (the
// fixed ones stay at these values); free: indices into values of the parameters in the block.
// Pairs with a pixel launch along the rig's ray through it; the others along their direction.
// context must outlive the cost functions.
std::vector<std::unique_ptr<ceres::CostFunction>> make_pair_costs(
    const FieldPtr& field, const std::vector<double>& values, const std::vector<int>& free,
    const std::vector<PointPair>& pairs, const PairOptions& options, Derivatives derivatives,
    const std::shared_ptr<const CameraRig>& rig, EvaluationContext* context);

}  // namespace refracta
