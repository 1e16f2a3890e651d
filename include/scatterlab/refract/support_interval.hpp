#pragma once
// Holzschuch 2013, §3.2: the support of each triangle's single-scattering contribution along an
// eye ray, so that an integrator samples the ray only where some triangle can refract light from
// the light to the scattering point V(x).
//
// For an eye-ray segment V(x) = origin + x direction, x in [t0, t1], inside the medium, the zeros
// of f(x, a, b) = H(x, a, b) + s N_s(a, b) (Walter eq. 8 with V moving, Holzschuch §3.2.2) form a
// curve; the triangle contributes at x when the curve's point lies in the triangle. The support
// interval [x_min, x_max] is found in three steps:
//  1. V(x) must lie below the triangle's plane and the light above it (sidedness about N_g, exact).
//  2. Flat triangles: an outer bound by bisection on x with a sound cone test on each
//     sub-segment: the directions from the triangle to the sub-segment (the six corner-to-end
//     directions span them), to the light, and the normal are bounded by cones. The cone of the
//     light's refracted directions (refracted_cone, computed once per light in RefractedLight)
//     must meet the directions to the sub-segment; then the sidedness, deviation (Holzschuch's
//     spindle-based test, §3.2.4) and half-vector overlap tests (Walter §3.3.1) reject
//     sub-segments on which no path exists. Leaves are 1/2 of the longest triangle edge.
//     Triangles with interpolated normals skip it: a triangle's cone of shading normals does not
//     narrow as the segment is bisected, and step 3's refinement over the triangle's parts bounds
//     their support on its own. On the bumpy sphere (10 080 triangles, 16 x 16 pixels, one
//     thread) the bisection cost 0.7-0.8 s of 4.1-4.7 s and removed 7.5 % of the triangles:
//     without it the image error (against 256 samples) is 0.021 at 32 samples in 3.9 s, with it
//     0.033 at 16 samples in 4.3 s.
//  3. Flat triangles: within that window, where a barycentric coordinate changes sign between the
//     window's ends, the curve crosses that edge line; the crossing (x, tau) is solved with the
//     pseudo-inverse Newton on the 3 x 2 system (Holzschuch §3.2.2), and the sign rules of §3.2.3
//     (d f / d x = lambda d f / d a + mu d f / d b, eq. 11; da/dx = -lambda, db/dx = -mu, eq. 12)
//     say whether it is a lower or an upper bound. Bisection on the flat refraction point takes
//     over where Newton fails. Exact (to the barycentric slack of accept_path) when the curve
//     crosses each edge line at most once inside the window, which the small window of step 2
//     makes the rule; a coordinate negative at both ends discards the triangle.
//     Triangles with interpolated normals: the curve may fold at caustics, so edge crossings
//     alone do not bound the support. Holzschuch §3.2.4's shading-normal test bounds it instead:
//     around a sphere holding a part of the triangle, the half-vector's cone must meet the
//     shading normals' cone, which along the ray is a point-to-hyperbola test giving an interval
//     of x. The test is applied to the whole triangle and, by branch and bound, to its parts down
//     to 4^6 of them, whose normal cones are narrow; the interval is the hull of theirs.
//  eta = 1: V must see the light through the triangle, the intersection of three half-spaces
//  (planes through the light and each edge), exact.
//
// Whole segments (§3.2.4): the position-normal tree's node bounds are tested against the segment
// with cones swept along it (axis from the ends' directions, widened by asin(r / d_min)), and the
// surviving triangles get their intervals.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "scatterlab/refract/position_normal_tree.hpp"
#include "scatterlab/refract/refraction_path.hpp"
#include "scatterlab/refract/refractive_solver.hpp"
#include "scatterlab/refract/triangle_search.hpp"

namespace scatterlab {

// V(x) = origin + x direction for x in [t0, t1]; direction is unit.
struct EyeSegment {
  Vec3 origin = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
  double t0 = 0.0, t1 = 0.0;

  Vec3 at(double x) const { return origin + x * direction; }
};

struct SupportInterval {
  double x_min = 0.0, x_max = 0.0;

  double length() const { return x_max - x_min; }
  bool contains(double x) const { return x_min <= x && x <= x_max; }
};

struct TriangleSupport {
  std::uint32_t triangle = 0;
  SupportInterval interval;
};

// Work counters, summed over segments.
struct SupportStats {
  std::uint64_t segments = 0;
  std::uint64_t nodes_visited = 0;
  std::uint64_t triangles_tested = 0;  // triangles that reached the per-triangle interval
  std::uint64_t cone_tests = 0;        // sub-segment tests of step 2
  std::uint64_t edge_newton_runs = 0;  // crossings solved by Newton (step 3)
  std::uint64_t edge_bisections = 0;   // crossings where Newton failed and bisection took over
  std::uint64_t supports = 0;          // non-empty intervals returned

  SupportStats& operator+=(const SupportStats& o);
};

// The light-side bounds, which depend on the light and not on the eye ray, built once per light:
// for every tree node and every triangle, the cone of directions in which light refracted there
// travels (refracted_cone). V can receive light from a triangle only in a direction from it within
// that cone: step 2 tests one cone overlap per sub-segment, and runs the half-vector test only
// where it passes.
//
// The whole triangle's cone also bounds its beam, the points light refracted through the
// triangle can reach: the Minkowski sum of the triangle and the cone. With the cone widened to
// the pyramid on a regular octagon around it, the beam is a polyhedron whose faces lie on planes
// through an edge and a side of the pyramid, through a corner and a face of the pyramid, or on
// the triangle's own plane; every such plane with the pyramid's sides behind it bounds the beam.
// An eye ray meets the beam in one interval (it is convex), found by clipping the ray with those
// planes before any cone test: most triangles near a ray send it no light and end there.
//
// Memory: one cone per triangle, two per tree node, and up to 33 planes (32 bytes each) per
// triangle (7 on average for the bumpy sphere).
class RefractedLight {
 public:
  RefractedLight(const RefractiveSolver& solver, const Light& light);

  // The most bytes one light's tables take for `triangles` triangles and `nodes` tree nodes
  // (planes at their bound per triangle, the per-thread chunks and the joined table both held),
  // so that a renderer can budget its lights before it builds them (core/memory_budget.hpp).
  static std::uint64_t table_bytes(std::size_t triangles, std::size_t nodes);

  const RefractiveSolver& solver() const { return *solver_; }
  const Light& light() const { return light_; }
  // A tree node's cones: of the directions to the light from its ball, and of the refracted ones.
  const DirectionCone& node_light(std::uint32_t index) const { return node_light_[index]; }
  const DirectionCone& node(std::uint32_t index) const { return nodes_[index]; }
  // A triangle's cone of refracted directions (none where no light enters it).
  const DirectionCone& refracted(std::uint32_t triangle) const { return refracted_[triangle]; }

  // A bounding plane of a triangle's beam: the beam lies where normal . X <= offset.
  struct BeamPlane {
    Vec3 normal;
    double offset;
  };
  // The triangle's beam planes (none where the cone is too wide to bound it).
  std::span<const BeamPlane> beam(std::uint32_t triangle) const {
    return {beam_planes_.data() + beam_first_[triangle],
            beam_first_[triangle + 1] - beam_first_[triangle]};
  }

 private:
  // Appends the planes of the beam of light refracted through tri within `cone`.
  static void add_beam_planes(const RefractiveTriangle& tri, const DirectionCone& cone,
                              std::vector<BeamPlane>& planes);

  const RefractiveSolver* solver_;
  Light light_;
  std::vector<DirectionCone> node_light_;
  std::vector<DirectionCone> nodes_;
  std::vector<DirectionCone> refracted_;
  std::vector<BeamPlane> beam_planes_;
  std::vector<std::size_t> beam_first_;  // triangle t's planes: [first[t], first[t + 1])
};

// Step 2's test: whether any V on the segment [va, vb] can receive a refracted path through the
// triangle. False only when none can (sound); eta = 1 uses the deviation test alone.
bool triangle_may_contribute(const RefractedLight& lit, std::uint32_t triangle, const Vec3& va,
                             const Vec3& vb);

// The same test for a tree node (its box bounded by a ball) and a segment.
bool node_may_contribute(const RefractedLight& lit, std::uint32_t node, const Vec3& va,
                         const Vec3& vb);

// The support interval of one triangle along the segment; nullopt when it cannot contribute.
std::optional<SupportInterval> triangle_support_interval(const RefractedLight& lit,
                                                         std::uint32_t triangle,
                                                         const EyeSegment& segment,
                                                         SupportStats& stats);

// Every triangle of the solver's mesh that can contribute somewhere on the segment, with its
// interval, in the order of the tree's depth-first leaves (the order find_paths visits them).
// Throws InputError for a segment with a non-unit direction or t1 < t0.
void find_segment_supports(const RefractedLight& lit, const EyeSegment& segment,
                           std::vector<TriangleSupport>& supports, SupportStats& stats);

}  // namespace scatterlab
