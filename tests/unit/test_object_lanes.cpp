// A convex object bounded by a triangle mesh on the lane walk (transport/object_boundary.hpp,
// mesh/mesh_light.hpp's object_boundary) against the one-photon RandomWalk on the same mesh and
// photons: a sphere of flat triangles, where the grid passes every flight that ends in a cell
// wholly inside, and a box, whose faces' planes pass every flight that ends inside; under a
// beam, the directional light and a sphere of light; matched, and behind a Fresnel boundary
// whose choices draw from the photon's stream. As in test_lane_walk.cpp the two walks follow the
// same paths: every photon scatters the same number of times, and every exitance cell (per
// triangle, split by order) agrees to 1e-9 of the largest. A mesh that is not convex is not
// given to the lanes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "every_target.hpp"
#include "mesh/mesh_boundary.hpp"
#include "mesh/mesh_light.hpp"
#include "scatterlab/core/phase_function.hpp"
#include "scatterlab/core/procedural_meshes.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/tally/tally_book.hpp"
#include "scatterlab/transport/lane_walk.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/random_walk.hpp"

namespace scatterlab {
namespace {

using testing::on_every_target;

template <bool fresnel, class Phase>
void expect_same_paths(const TriangleMesh& mesh, double albedo, const Phase& phase, double eta,
                       typename MeshLight<fresnel>::Kind kind) {
  SCOPED_TRACE(::testing::Message() << "light " << static_cast<int>(kind) << ", eta " << eta);
  LitObjectSpec spec;
  spec.mesh = std::make_shared<const TriangleMesh>(mesh);
  spec.mesh_source = "test";
  spec.medium.albedo = albedo;
  spec.medium.g = phase.mean_cosine();
  spec.eta = eta;
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const MeshRayTracer tracer(mesh);
  const MeshBoundary<fresnel> boundary(tracer, mesh, eta);
  // A beam along z a hair off the axis, the directional light along (0.1, 0, 1) over the sphere
  // of radius 3 about the origin that holds the mesh, or a sphere of light of radius 0.5 below.
  using Kind = typename MeshLight<fresnel>::Kind;
  const Vec3 origin = kind == Kind::sphere ? Vec3(0.1, 0.2, -4.0) : Vec3(1e-3, 2e-3, -6.0);
  const MeshLight<fresnel> light(boundary, kind, origin,
                                 kind == Kind::beam ? Vec3::UnitZ() : Vec3(0.1, 0.0, 1.0),
                                 Vec3::Zero(), kind == Kind::sphere ? 0.5 : 3.0);
  const RandomWalk<MeshBoundary<fresnel>, Phase, Estimator::none, Weighting::analog,
                   MeshLight<fresnel>>
      one(boundary, phase, light, scorer, albedo, problem.run.escape_radius, problem.run.seed);
  // A range that does not start at 0 and is no multiple of any lane count.
  const std::uint64_t first = 1001, last = 3004;
  std::vector<double> a(book.size(), 0.0);
  std::vector<double> scratch;
  const std::uint64_t a_scatterings = one.run(first, last, a.data(), scratch);
  ASSERT_GT(a_scatterings, 0u);
  double largest = 0.0;
  for (const double v : a) largest = std::max(largest, std::abs(v));
  on_every_target([&] {
    const LaneWalk lanes(*object_boundary(boundary, light), scorer, albedo, phase.mean_cosine(),
                         Estimator::none, problem.run.escape_radius, problem.run.seed);
    std::vector<double> b(book.size(), 0.0);
    EXPECT_EQ(lanes.run(first, last, b.data(), scratch), a_scatterings);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i) differing += std::abs(a[i] - b[i]) > 1e-9 * largest;
    EXPECT_EQ(differing, 0u) << "of " << a.size() << " cells";
  });
}

TEST(ObjectLanes, FollowTheOnePhotonWalkInAConvexMesh) {
  const TriangleMesh sphere = make_sphere(2.0, 16, 32, false);
  ASSERT_TRUE(bounds_convex_solid(sphere));
  using Light = MeshLight<true>;
  expect_same_paths<true>(sphere, 0.99, IsotropicPhase{}, 1.33, Light::Kind::beam);
  expect_same_paths<true>(sphere, 0.9, HenyeyGreenstein{0.75}, 1.4, Light::Kind::directional);
  expect_same_paths<false>(sphere, 0.95, HenyeyGreenstein{-0.3}, 1.0,
                           MeshLight<false>::Kind::sphere);
  // A box, whose six planes decide every flight in place of the core and the grid.
  const TriangleMesh box = make_box(Vec3(2.0, 1.5, 1.0));
  ASSERT_EQ(MeshBoundary<true>(MeshRayTracer(box), box, 1.33).interior().faces, 6);
  expect_same_paths<true>(box, 0.99, IsotropicPhase{}, 1.33, Light::Kind::beam);
  expect_same_paths<true>(box, 0.9, HenyeyGreenstein{0.75}, 1.4, Light::Kind::directional);
}

TEST(ObjectLanes, AreNotGivenAMeshThatIsNotConvex) {
  const TriangleMesh bumpy = make_bumpy_sphere(2.0, 0.25, 4, 24, 48);
  const MeshRayTracer tracer(bumpy);
  const MeshBoundary<true> boundary(tracer, bumpy, 1.33);
  const MeshLight<true> light(boundary, MeshLight<true>::Kind::directional, Vec3::Zero(),
                              Vec3::UnitZ(), Vec3::Zero(), 3.0);
  EXPECT_FALSE(object_boundary(boundary, light).has_value());
}

TEST(ObjectLanes, RefuseTheTrackLengthEstimator) {
  const TriangleMesh sphere = make_sphere(1.0, 8, 16, false);
  LitObjectSpec spec;
  spec.mesh = std::make_shared<const TriangleMesh>(sphere);
  const TransportProblem problem = transport_problem(spec);
  const TallyBook book(problem.tallies, problem.split_by_order);
  const Scorer scorer(problem.axes, book);
  const MeshRayTracer tracer(sphere);
  const MeshBoundary<false> boundary(tracer, sphere, 1.0);
  const MeshLight<false> light(boundary, MeshLight<false>::Kind::directional, Vec3::Zero(),
                               Vec3::UnitZ(), Vec3::Zero(), 1.0);
  EXPECT_THROW(LaneWalk(*object_boundary(boundary, light), scorer, 0.9, 0.0,
                        Estimator::track_length, 1e3, 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace scatterlab
