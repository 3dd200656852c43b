#pragma once
// The surface the simulated objects touch each other with (scene
// `contact: {self: true}`): every object's triangles over global particle
// indices (a cloth's mesh, a solid's boundary faces), with the contact
// parameters. The solvers detect vertex-triangle and edge-edge pairs on it.
#include <array>
#include <optional>
#include <vector>

#include "model/model.hpp"
#include "scene/contact_desc.hpp"

namespace atssim::model {

// Empty when the scene's contact is off. Throws atssim::Error (input) when
// the thickness is not below half the shortest surface edge: triangles two
// rings apart would then push each other away at rest.
std::optional<ContactSurface> make_contact_surface(const scene::SelfContactDesc& desc, const Model& model);

}  // namespace atssim::model
