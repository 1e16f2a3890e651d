// Which closed meshes bound a convex solid (render/convex_mesh.hpp): light leaving those never
// comes back, so the mesh's transport skips the search for a re-entry.
#include <gtest/gtest.h>

#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/render/convex_mesh.hpp"
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

}  // namespace
}  // namespace scatterlab
