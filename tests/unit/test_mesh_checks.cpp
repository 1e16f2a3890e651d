// A mesh is refused where transport by crossing parity would be wrong or a read would leave the
// file's arrays: a surface that passes through itself, a sphere of light that cuts into the
// object between its vertices, an OBJ face that names a vertex or normal the file does not have.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "render/obj_mesh.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/mesh/mesh_checks.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {
namespace {

// The InputError's text, or "" when `check` accepts.
template <class Check>
std::string refusal(Check check) {
  try {
    check();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TriangleMesh two_boxes(const Vec3& shift) {
  TriangleMesh mesh = make_box(Vec3(1.0, 1.0, 1.0));
  append_mesh(mesh, make_box(Vec3(1.0, 1.0, 1.0)), shift);
  return mesh;
}

TEST(MeshChecks, OverlappingClosedPartsAreRefused) {
  const TriangleMesh overlapping = two_boxes(Vec3(1.0, 0.5, 0.25));
  require_closed_mesh(overlapping);  // each part is closed: only the crossing test sees it
  EXPECT_NE(refusal([&] { require_no_self_intersection(overlapping); }).find("intersects itself"),
            std::string::npos);
}

TEST(MeshChecks, SurfacesThatDoNotCrossAreAccepted) {
  EXPECT_EQ(refusal([] { require_no_self_intersection(make_box(Vec3(1.0, 2.0, 3.0))); }), "");
  EXPECT_EQ(refusal([] { require_no_self_intersection(two_boxes(Vec3(3.0, 0.0, 0.0))); }), "");
  TriangleMesh nested = make_box(Vec3(2.0, 2.0, 2.0));
  append_mesh(nested, make_box(Vec3(0.5, 0.5, 0.5)), Vec3(0.3, -0.2, 0.1));
  EXPECT_EQ(refusal([&] { require_no_self_intersection(nested); }), "");
  // Not convex, with many short edges meeting at shallow angles.
  EXPECT_EQ(refusal([] { require_no_self_intersection(make_bumpy_sphere(4.0, 0.15, 5, 41, 48)); }),
            "");
}

TEST(MeshChecks, ASphereOfLightThatCutsAFaceBetweenItsVerticesIsRefused) {
  LitObjectSpec spec;
  spec.mesh = std::make_shared<const TriangleMesh>(make_box(Vec3(10.0, 10.0, 10.0)));
  spec.light = ObjectLight::sphere;
  spec.light_center = {0.0, 0.0, -11.0};  // 1 below the bottom face's centre, 14 from a corner
  spec.light_radius = 2.0;
  EXPECT_NE(refusal([&] { check_lit_mesh(spec); }).find("source.radius"), std::string::npos);
  spec.light_radius = 0.99;
  EXPECT_EQ(refusal([&] { check_lit_mesh(spec); }), "");
}

TEST(MeshChecks, OBJFaceIndicesOutsideTheFileAreRefused) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n";
  EXPECT_NE(refusal([&] {
              parse_obj_mesh(square + "f 1 2 9\n", "far.obj", false);
            }).find("a face names vertex 9 but the file has 4"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              parse_obj_mesh(square + "f 1//1 2//1 3//2\n", "n.obj", true);
            }).find("a face names normal 2 but the file has 1"),
            std::string::npos);
  // A material library is never opened: the mesh reads the same with or without it.
  const TriangleMesh with_library =
      parse_obj_mesh("mtllib /etc/passwd\n" + square + "f 1 2 3\n", "m.obj", false);
  EXPECT_EQ(with_library.triangle_count(), 1u);
}

}  // namespace
}  // namespace scatterlab
