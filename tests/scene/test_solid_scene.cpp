#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "scene/scene_loader.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

std::string error_of(const std::string& yaml, std::vector<std::string> overrides = {}) {
  try {
    scene::parse_scene(yaml, "scene.yaml", ".", overrides);
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    const std::string msg = e.what();
    CHECK(msg.find('\n') == std::string::npos);
    return msg;
  }
  return "";
}

const std::string kBox =
    "objects:\n"
    "  - name: jelly\n"
    "    type: solid\n"
    "    box: {size: [0.4, 0.2, 0.3], resolution: [4, 2, 3]}\n"
    "    material:\n"
    "      density: 500\n"
    "      youngs_modulus: 2.0e5\n"
    "      poisson_ratio: 0.45\n"
    "      model: stvk\n";

}  // namespace

TEST_CASE("a solid box is read with its shape and material") {
  const auto s = scene::parse_scene(kBox, "scene.yaml", ".");
  REQUIRE(s.objects.size() == 1);
  const auto& o = s.objects[0];
  CHECK(o.type == scene::ObjectType::solid);
  REQUIRE(o.box);
  CHECK(o.box->resolution == std::array<int, 3>{4, 2, 3});
  CHECK(o.box->size[1] == 0.2);
  CHECK(o.material.density == 500.0);
  CHECK(o.material.youngs_modulus == 2.0e5);
  CHECK(o.material.poisson_ratio == 0.45);
  CHECK(o.material.solid_model == scene::SolidModel::stvk);
}

TEST_CASE("solids default to neo-Hookean and 1000 kg/m³, and cloth stays the default type") {
  const auto s = scene::parse_scene("objects:\n  - {type: solid, box: {}}\n  - grid: {}\n", "scene.yaml", ".");
  CHECK(s.objects[0].material.solid_model == scene::SolidModel::neo_hookean);
  CHECK(s.objects[0].material.density == 1000.0);
  CHECK(s.objects[1].type == scene::ObjectType::cloth);
  CHECK(s.objects[1].material.density == 0.2);
}

TEST_CASE("the resolved scene of a solid reads back to the same description") {
  const auto s =
      scene::parse_scene(kBox, "scene.yaml", ".", std::vector<std::string>{"objects.0.material.model=springs"});
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  const auto& a = again.objects[0];
  CHECK(a.type == scene::ObjectType::solid);
  CHECK(a.box->size == s.objects[0].box->size);
  CHECK(a.box->resolution == s.objects[0].box->resolution);
  CHECK(a.material.youngs_modulus == 2.0e5);
  CHECK(a.material.poisson_ratio == 0.45);
  CHECK(a.material.solid_model == scene::SolidModel::springs);
}

TEST_CASE("cloth keys on a solid and solid keys on a cloth are errors that say so") {
  std::string msg = error_of(kBox + "      stretch_stiffness: 100\n");
  CHECK(msg.find("scene.yaml:10:") == 0);
  CHECK(msg.find("'stretch_stiffness' is a cloth material key, but object 'jelly' is a solid") != std::string::npos);

  msg = error_of("objects:\n  - grid: {}\n    material: {youngs_modulus: 1e5}\n");
  CHECK(msg.find("scene.yaml:3:") == 0);
  CHECK(msg.find("'youngs_modulus' is a solid material key") != std::string::npos);
  CHECK(msg.find("type: solid") != std::string::npos);

  CHECK(error_of("objects:\n  - {type: solid, grid: {}}\n").find("'grid' makes a cloth") != std::string::npos);
  CHECK(error_of("objects:\n  - {box: {}}\n").find("'box' makes a solid") != std::string::npos);
  CHECK(error_of("objects:\n  - {type: solid}\n").find("exactly one of 'box' or 'mesh'") != std::string::npos);
  CHECK(error_of("objects:\n  - {type: jelly, box: {}}\n").find("unknown object type 'jelly'") != std::string::npos);
}

TEST_CASE("misspelt solid keys and values get did-you-mean suggestions") {
  CHECK(error_of(kBox, {"objects.0.material.youngs_modulos=1"}).find("did you mean 'youngs_modulus'?") !=
        std::string::npos);
  CHECK(error_of(kBox, {"objects.0.material.model=neo_hooken"}).find("did you mean 'neo_hookean'?") !=
        std::string::npos);
}

TEST_CASE("solid material values out of range name the valid range") {
  CHECK(error_of(kBox, {"objects.0.material.poisson_ratio=0.5"}).find("0 ≤ ν < 0.5") != std::string::npos);
  CHECK(error_of(kBox, {"objects.0.material.poisson_ratio=-0.1"}).find("out of range") != std::string::npos);
  CHECK(error_of(kBox, {"objects.0.material.youngs_modulus=0"}).find("Young's modulus in Pa > 0") != std::string::npos);
  CHECK(error_of(kBox, {"objects.0.box.resolution=[4, 0, 1]"}).find("out of range") != std::string::npos);
  CHECK(error_of(kBox, {"objects.0.box.resolution=[4, 4]"}).find("three entries") != std::string::npos);
  CHECK(error_of(kBox, {"objects.0.box.size=[1, -1, 1]"}).find("must be positive") != std::string::npos);
}

TEST_CASE("a solid needs a tet mesh file and a cloth a surface mesh file") {
  test::TempDir dir;
  dir.write("body.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  dir.write("body.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
            "$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n");
  const auto path = dir.write("s.yaml", "objects:\n  - {type: solid, mesh: body.obj}\n");
  CHECK_THROWS_WITH(scene::load_scene_file(path), Catch::Contains("is not a tetrahedral mesh"));
  dir.write("s.yaml", "objects:\n  - {mesh: body.msh}\n");
  CHECK_THROWS_WITH(scene::load_scene_file(path), Catch::Contains("add 'type: solid'"));
  dir.write("s.yaml", "objects:\n  - {type: solid, mesh: body.msh}\n");
  const auto s = scene::load_scene_file(path);
  CHECK(s.objects[0].tet_mesh.tetrahedra.size() == 1);
  CHECK(s.resolved_yaml.find("body.msh") != std::string::npos);
}
