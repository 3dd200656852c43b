#pragma once
// Builds the tetrahedral solids of a scene (issue #6): vertices placed by the
// transform, every element validated, lumped masses from density × volume,
// pins, rest data and Lamé parameters in Model::tets, and the outward
// surface in the object's triangles.
#include <string>

#include "model/model.hpp"
#include "scene/scene_desc.hpp"

namespace atssim::model {

struct LameParameters {
  double mu = 0.0;      // shear modulus, Pa
  double lambda = 0.0;  // Pa
};

// μ = E / (2(1+ν)), λ = E ν / ((1+ν)(1−2ν)) (requires E > 0, 0 ≤ ν < 0.5).
LameParameters lame_parameters(double youngs_modulus, double poisson_ratio);

// Signed volumes of the tets of `mesh` at `rest` (world) positions, after
// checking them: an element whose volume is not clearly positive is an input
// error naming it — by file line and the file's own element number when the
// mesh came from a file, by index and the object's scene line otherwise. A
// mesh whose every element is negative was written with the opposite vertex
// order convention; its tets are flipped (two vertices swapped) instead.
std::vector<double> checked_volumes(scene::TetMesh& mesh, const std::vector<Vec3>& rest, const scene::ObjectDesc& obj,
                                    const std::string& scene_file);

// Appends one solid object (obj.type == solid) to the model. Throws
// atssim::Error (input) for an invalid element or pin.
void add_solid(Model& model, const scene::ObjectDesc& obj, const std::string& scene_file);

}  // namespace atssim::model
