#pragma once
// Where a ray crosses the surface of a convex mesh, found by walking from facet to facet across
// their edges instead of by a query of the whole mesh: the exit of almost every photon that
// leaves a convex object, and the entry of light from outside (mesh_boundary.hpp).
//
// A ray p + t d passes through the triangle a, b, c exactly when d lies in the cone of its
// corners seen from p, that is when the three products
//   ((a - p) x (b - p)) . d,  ((b - p) x (c - p)) . d,  ((c - p) x (a - p)) . d
// share a sign (each is the signed volume of p, an edge and p + d: the side of the edge's
// plane through p that d points to). The facets are counter-clockwise seen from outside, so the
// sign is + for the facet a ray from inside leaves by, and - for the facet a ray from outside
// enters by (d = sum of l_i (v_i - p), l_i >= 0, gives l_c det(a - p, b - p, c - p), whose sign
// is the side of the facet's plane p lies on).
//
// Seen from a point inside a convex solid, the facets tile the sphere of directions; seen from
// outside along d, the facets facing the light tile the object's convex shadow. Either way a
// product of the wrong sign says the ray passes beyond that edge, and the walk crosses it into
// the facet across, as a point is located in a triangulation by walking (Devillers, Pion &
// Teillaud 2002, "Walking in a triangulation", §2: the visibility walk, here never crossing
// back the edge it came by, and trying the edges in turn from a different one at each step so
// that it does not cycle). Coming in from outside, a walk that steps onto a facet facing away
// from the light has crossed the rim of the shadow, which is convex: the ray misses.
//
// Each product is computed from the Plücker coordinates of the edge's line and of the ray
// (Platis & Theoharis 2003, "Fast ray-tetrahedron intersection using Plücker coordinates",
// J. Graphics Tools 8(4), §2): expanding the cross product,
//   ((a - p) x (b - p)) . d = (a x b) . d + ((b - a) x p) . d = (a x b) . d + (b - a) . (p x d),
// so an edge keeps a x b and b - a, a walk computes p x d once, and a product is two dot
// products (all about the centroid, so that no large coordinates cancel).
//
// Watertight: an edge's coordinates are stored once, from its lower corner to its higher, for
// both facets that share it, and the facet that runs the edge the other way negates the
// product, so that a ray through an edge is claimed by at least one facet and never lost
// between two, however the products are rounded.
//
// The walk starts at the facet met, from the object's centroid, in the direction of a point
// near where the ray is expected to cross (a table over the octahedral map of directions,
// about four cells a facet): where the ray leaves, or enters, the ball about the centroid that
// holds the object (a line that misses the ball misses the object, and needs no walk). A walk that
// has not arrived within 64 + 4 sqrt(facets) steps (none was seen in the tests), or arrives at a
// facet the ray grazes, gives up, and the caller asks Embree.

#include <array>
#include <cstdint>
#include <vector>

#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"

namespace scatterlab {

class ConvexCrossing {
 public:
  // `mesh` is closed, consistently oriented and bounds a convex solid (bounds_convex_solid);
  // `tracer` is over it and is used only here, to fill the table of starting facets.
  ConvexCrossing(const TriangleMesh& mesh, const MeshRayTracer& tracer);

  enum class Walk { crosses, misses, gave_up };

  // The facet through which the ray from `origin` (inside, or on the surface) along the unit
  // `direction` leaves: crosses (`at` the crossing, at a distance >= 0, and `cos_incidence`
  // = |direction . normal| > 0), or gave_up.
  Walk leave(const Vec3& origin, const Vec3& direction, MeshCrossing& at,
             double& cos_incidence) const;

  // The facet through which the ray from `origin` (outside) along the unit `direction` enters,
  // starting from the facet towards where the line comes within the object's bounding ball:
  // crosses (at a distance > 0), misses (also when the object lies behind the origin), or
  // gave_up.
  Walk enter(const Vec3& origin, const Vec3& direction, MeshCrossing& at,
             double& cos_incidence) const;

  // The centroid of the facets, inside, and its distance to the nearest facet's plane: the
  // radius of the largest ball about it inside the object.
  const Vec3& centroid() const { return centroid_; }
  // The outward unit normal of facet `t` (TriangleMesh::geometric_normal).
  const Vec3& normal(std::uint32_t t) const { return planes_[t].normal; }
  double inner_radius() const { return inner_radius_; }

 private:
  // An edge's line, from its lower corner a to its higher b (indices of positions, shared across
  // seams), about the centroid: the product of the ray p + t d with it is
  // (a x b) . d + (b - a) . (p x d).
  struct Edge {
    Vec3 moment;  // a x b
    Vec3 along;   // b - a
  };
  // What a step of the walk reads of a facet, in half a cache line: its edges (edge k runs from
  // corner k to corner k + 1), the facets across them, and which run from the lower corner to
  // the higher (bit k), whose product is then the facet's own, and not its negative.
  struct Facet {
    std::array<std::uint32_t, 3> edge;
    std::array<std::uint32_t, 3> across;
    std::uint32_t rising = 0;
  };
  // Read on arrival only.
  struct Plane {
    Vec3 normal;          // outward unit normal
    double offset = 0.0;  // normal . corner
  };

  std::uint32_t start(const Vec3& near) const;
  // The walk, for products of sign `inward` (+1 leaving, -1 entering).
  Walk walk(double inward, const Vec3& origin, const Vec3& direction, std::uint32_t from,
            MeshCrossing& at, double& cos_incidence) const;

  std::vector<Edge> edges_;
  std::vector<Facet> facets_;
  std::vector<Plane> planes_;
  Vec3 centroid_;
  double radius_ = 0.0;  // of the ball about the centroid that holds the object
  double inner_radius_ = 0.0;
  int map_cells_ = 1;                 // per side of the octahedral map
  std::vector<std::uint32_t> start_;  // facet met in each cell's direction
  int max_steps_ = 0;
};

}  // namespace scatterlab
