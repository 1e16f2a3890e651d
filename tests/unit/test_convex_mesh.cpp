// Which closed meshes bound a convex solid (mesh/convex_mesh.hpp): light leaving those never
// comes back, so the mesh's transport skips the search for a re-entry. The planes of a convex
// polyhedron of few faces, which decide where a flight ends (mesh_boundary.hpp), against the
// box they come from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "mesh/convex_mesh.hpp"
#include "mesh/mesh_boundary.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {
namespace {

TEST(ConvexMesh, SpheresAndBoxesAreConvexBumpsAndTwoPiecesAreNot) {
  EXPECT_TRUE(bounds_convex_solid(make_sphere(2.0, 24, 48, false)));
  EXPECT_TRUE(bounds_convex_solid(make_sphere(1e-3, 96, 192, true)));  // tiny, fine facets
  EXPECT_TRUE(bounds_convex_solid(make_box(Vec3(1.0, 2.0, 0.3))));
  EXPECT_FALSE(bounds_convex_solid(make_bumpy_sphere(3.0, 0.05, 5, 41, 48)));
  // Two boxes, each convex, side by side: light leaving one can enter the other.
  TriangleMesh two = make_box(Vec3(1.0, 1.0, 1.0));
  append_mesh(two, make_box(Vec3(1.0, 1.0, 1.0)), Vec3(3.0, 0.0, 0.0));
  EXPECT_FALSE(bounds_convex_solid(two));
  // An open mesh bounds no solid.
  EXPECT_FALSE(bounds_convex_solid(make_flat_square(1.0, 1)));
}

// The triangle across each edge, which both the convexity test and the convex mesh's surface
// walk read: in a closed box, a different triangle holding the same edge reversed, and across
// that one's edge the first again; in an open square, none across the rim.
TEST(ConvexMesh, EachEdgeIsSharedWithTheTriangleAcrossItOrWithNone) {
  const TriangleMesh box = make_box(Vec3(1.0, 2.0, 0.3));
  const std::vector<std::uint32_t> id = vertex_ids_by_position(box);
  const auto across = triangles_across_edges(box, id);
  ASSERT_EQ(across.size(), box.triangle_count());
  const auto corner = [&](std::size_t t, std::size_t k) { return id[box.triangles[t][k % 3]]; };
  for (std::size_t t = 0; t < box.triangle_count(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t u = across[t][k];
      ASSERT_NE(u, no_triangle);
      ASSERT_NE(u, t);
      int reversed = 0;
      for (std::size_t j = 0; j < 3; ++j) {
        if (corner(u, j) == corner(t, k + 1) && corner(u, j + 1) == corner(t, k)) {
          ++reversed;
          EXPECT_EQ(across[u][j], t);
        }
      }
      EXPECT_EQ(reversed, 1);
    }
  }
  const TriangleMesh square = make_flat_square(1.0, 1);
  const auto open = triangles_across_edges(square, vertex_ids_by_position(square));
  int rim = 0, shared = 0;
  for (const auto& edges : open) {
    for (const std::uint32_t u : edges) (u == no_triangle ? rim : shared) += 1;
  }
  EXPECT_EQ(rim, 4);
  EXPECT_EQ(shared, 3 * static_cast<int>(square.triangle_count()) - 4);
}

TEST(ConvexMesh, ABoxHasSixFacePlanesATessellatedSphereTooMany) {
  const Vec3 half(1.0, 2.0, 0.3), about(0.1, -0.2, 0.05);
  const std::vector<FacePlane> planes = face_planes(make_box(half), about, 8);
  ASSERT_EQ(planes.size(), 6u);
  for (const FacePlane& plane : planes) {
    // An axis, outward, at the face's distance from `about`.
    int axis = 0;
    plane.normal.cwiseAbs().maxCoeff(&axis);
    EXPECT_DOUBLE_EQ(std::abs(plane.normal[axis]), 1.0);
    const double side = plane.normal[axis];
    EXPECT_NEAR(plane.offset, half[axis] - side * about[axis], 1e-15);
  }
  EXPECT_TRUE(face_planes(make_sphere(2.0, 24, 48, false), about, 8).empty());
  EXPECT_EQ(face_planes(make_box(half), about, 5).size(), 0u);  // six is more than five
}

// The mesh's interior test, by the planes, against the box itself: every point it passes lies
// inside, and it passes every point farther than 1e-6 inside (its margin is 1e-9 of the box's
// diagonal).
TEST(ConvexMesh, ABoxsPlanesPassExactlyThePointsInside) {
  const Vec3 half(1.0, 2.0, 0.3);
  TriangleMesh box = make_box(half);
  for (Vec3& p : box.positions) p += Vec3(5.0, -3.0, 1.0);
  const MeshRayTracer tracer(box);
  const MeshBoundary<true> boundary(tracer, box, 1.33);
  ASSERT_EQ(boundary.interior().faces, 6);
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int passed = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 local(u(engine) * half.x(), u(engine) * half.y(), u(engine) * half.z());
    const double depth = (half - local.cwiseAbs()).minCoeff();  // < 0 outside
    const bool inside = boundary.interior().inside(local + Vec3(5.0, -3.0, 1.0));
    if (inside) {
      EXPECT_GT(depth, 0.0) << local.transpose();
    }
    if (depth > 1e-6) {
      EXPECT_TRUE(inside) << local.transpose();
    }
    passed += inside;
  }
  EXPECT_GT(passed, 0);
}

}  // namespace
}  // namespace scatterlab
