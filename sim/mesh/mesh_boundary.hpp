#pragma once
// A closed triangle mesh filled with the medium, behind a smooth interface of relative index
// eta = n_medium / n_outside: a geometry of the transport engine's random walk
// (transport/random_walk.hpp), traced with Embree (mesh_ray_tracer.hpp). Vavassori §4.3 fills
// such objects with measured media; Bitterli 2013, Alg. 1 gives the boundary's analog choice.
//
// Inside, a flight that meets the surface is reflected with probability F(cos theta_i) (always
// under total internal reflection) and flies on for the rest of its sampled path (the free path
// is memoryless), or leaves, refracted (as at the half-space's surface, half_space.hpp). The
// normal is the facet's geometric one: shading normals smooth an image, not the object light
// actually crosses.
//
// A shape that is not convex can take the light back: a photon that leaves is followed outside
// in a straight line, and where it meets the mesh again it is reflected off it (probability F,
// and followed on) or refracted in, where it starts a fresh flight (an exponential free path:
// nothing of the old one carries over a stretch of vacuum). It leaves for good when its line
// meets the mesh no more. The exit tallies see only that last departure (the triangle it left
// through for good): light that leaves and comes back is not counted where it left.
//
// Most flights of a large object end far from its surface, and need no ray query: one whose
// length is under the clearance of its start (surface_clearance.hpp), or, in a convex object
// (convex_mesh.hpp), one that ends in its core (a ball inside it) or in a cell wholly inside.
// A photon leaving a convex object does not look for its way back in, and light finds where it
// enters or leaves a convex object by a walk over the facets (convex_crossing.hpp) rather than
// by a query of the whole mesh.
//
// `fresnel` = false is the index-matched object (eta = 1): light crosses without reflection or
// bending, and no random number is drawn at the surface but the fresh flight after a re-entry.

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "convex_crossing.hpp"
#include "convex_mesh.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/tally/surface_exit.hpp"
#include "surface_clearance.hpp"

namespace scatterlab {

// The meeting of a ray from `origin` along the unit `direction` with the mesh in
// (t_near, t_far); false when there is none.
inline bool next_crossing(const MeshRayTracer& tracer, const TriangleMesh& mesh, const Vec3& origin,
                          const Vec3& direction, double t_near, double t_far,
                          MeshCrossing& crossing) {
  MeshHit hit;
  if (!tracer.intersect(origin, direction, t_near, t_far, hit)) return false;
  const Vec3& p0 = mesh.vertex(hit.triangle, 0);
  const Vec3& p1 = mesh.vertex(hit.triangle, 1);
  const Vec3& p2 = mesh.vertex(hit.triangle, 2);
  crossing.point = (1.0 - hit.bary_a - hit.bary_b) * p0 + hit.bary_a * p1 + hit.bary_b * p2;
  crossing.normal = (p1 - p0).cross(p2 - p0).normalized();
  crossing.triangle = hit.triangle;
  crossing.distance = hit.distance;
  return true;
}

template <bool fresnel>
class MeshBoundary {
 public:
  static constexpr bool has_surface = true;
  static constexpr bool layered = false;

  // `tracer` is over `mesh`; both outlive the boundary.
  MeshBoundary(const MeshRayTracer& tracer, const TriangleMesh& mesh, double eta)
      : tracer_(&tracer),
        mesh_(&mesh),
        eta_(eta),
        epsilon_(tracer.epsilon()),
        clearance_(std::make_shared<const SurfaceClearance>(mesh, tracer)),
        crossing_(bounds_convex_solid(mesh) ? std::make_shared<const ConvexCrossing>(mesh, tracer)
                                            : nullptr),
        interior_(clearance_->interior()) {
    // A convex object's core: the largest ball about the walk's centroid that its facets'
    // planes leave whole, a millionth smaller.
    const double core = crossing_ ? crossing_->inner_radius() * (1.0 - 1e-6) : 0.0;
    if (core > 0.0) {
      interior_.core_centre = crossing_->centroid();
      interior_.core_radius2 = core * core;
      // A polyhedron of few faces: its planes, held 1e-9 of its size inside, far beyond the
      // 1e-12 by which the facets that share a plane may differ from it over the object.
      const double margin = 1e-9 * mesh.bounds().diagonal();
      const std::vector<FacePlane> planes = face_planes(
          mesh, interior_.core_centre, static_cast<std::size_t>(InteriorClearance::max_faces));
      for (const FacePlane& plane : planes) {
        const int i = interior_.faces++;
        interior_.face_x[i] = plane.normal.x();
        interior_.face_y[i] = plane.normal.y();
        interior_.face_z[i] = plane.normal.z();
        interior_.face_offset[i] = plane.offset - margin;
      }
    }
  }

  const MeshRayTracer& tracer() const { return *tracer_; }
  const TriangleMesh& mesh() const { return *mesh_; }
  // The grid of clearances inside the object, which the lane walk reads, and whether the
  // object is convex, which the lane walk needs (transport/object_boundary.hpp).
  const InteriorClearance& interior() const { return interior_; }
  bool convex() const { return crossing_ != nullptr; }
  // The outward unit normal of triangle `t`: the walk's, in a convex object.
  Vec3 facet_normal(std::uint32_t t) const {
    return crossing_ ? crossing_->normal(t) : mesh_->geometric_normal(t);
  }

  // The light outside at `position`, travelling along `direction`, meets the mesh (or not):
  // reflected off it with probability F and followed on, or refracted in. True when it enters
  // (position and direction then inside, at the surface); false when it goes off to infinity.
  // `t_near`: skip the surface the ray starts on. `met`, when given, says whether the light met
  // the mesh at all.
  bool enter(Vec3& position, Vec3& direction, PhotonRandom& random, double t_near,
             bool* met = nullptr) const {
    MeshCrossing at;
    double cos_outside = 0.0;
    if (!first_entry(position, direction, t_near, at, cos_outside)) return false;
    if (met != nullptr) *met = true;
    return enter_at(at, cos_outside, fresnel ? random.next4()[0] : 0.0, position, direction,
                    random);
  }

  // The first crossing of the light outside at `position` along `direction` with the mesh,
  // met from outside, beyond `t_near`, and the cosine of incidence; false when there is none.
  // In a convex object, by the walk over the facets facing the light (convex_crossing.hpp).
  bool first_entry(const Vec3& position, const Vec3& direction, double t_near, MeshCrossing& at,
                   double& cos_outside) const {
    const ConvexCrossing::Walk walk = crossing_
                                          ? crossing_->enter(position, direction, at, cos_outside)
                                          : ConvexCrossing::Walk::gave_up;
    if (walk == ConvexCrossing::Walk::misses) return false;
    if (walk == ConvexCrossing::Walk::crosses && at.distance > t_near) return true;
    return next_facing(true, position, direction, t_near, infinity, at, cos_outside);
  }

  // enter() from its first crossing `at` (first_entry): a light whose first crossing is always
  // the same (a beam) finds it once. `u` is the uniform of the Fresnel choice there (unused
  // where eta = 1), so that a light may draw it with its own; the choices where light
  // reflected off an object that is not convex meets it again draw from `random`.
  bool enter_at(MeshCrossing at, double cos_outside, double u, Vec3& position, Vec3& direction,
                PhotonRandom& random) const {
    for (;;) {
      position = at.point;
      if constexpr (fresnel) {
        const FresnelDielectric surface = fresnel_dielectric_terms(cos_outside, eta_);
        if (u < surface.reflectance()) {
          direction = (direction + 2.0 * cos_outside * at.normal).normalized();
          // Light reflected off a convex object never meets it again.
          if (convex() ||
              !next_facing(true, position, direction, epsilon_, infinity, at, cos_outside)) {
            return false;
          }
          u = random.next4()[0];
          continue;
        }
        direction = refracted(direction, at.normal, eta_, cos_outside, surface.cos_transmitted);
      }
      return true;
    }
  }

  // The walk's surface (random_walk.hpp): the flight of `flight` mfp from `position` along
  // `direction` that would end at `next`. Either the photon leaves for good (true, `exit`
  // filled) or the flight goes on inside, after reflections or a re-entry, to end at `next`.
  bool leaves(Vec3& position, Vec3& direction, Vec3& next, double flight, PhotonRandom& random,
              SurfaceExit& exit) const {
    if (convex() ? ends_inside(next) : flight < clearance_->at(position)) return false;
    return meets_surface(position, direction, next, flight, random, exit);
  }

  // leaves() past its first test, for a caller that has made it: the lane walk, which reads
  // the same interior for all lanes at once (transport/object_boundary.hpp).
  bool meets_surface(Vec3& position, Vec3& direction, Vec3& next, double flight,
                     PhotonRandom& random, SurfaceExit& exit) const {
    double t_near = 0.0;
    MeshCrossing at;
    double cos_inside = 0.0;
    while (next_exit(position, direction, t_near, flight, at, cos_inside)) {
      t_near = epsilon_;
      const Vec3& normal = at.normal;
      position = at.point;
      if constexpr (fresnel) {
        const FresnelDielectric surface = fresnel_dielectric_terms(cos_inside, 1.0 / eta_);
        if (surface.total_internal_reflection || random.next4()[0] < surface.reflectance()) {
          flight -= at.distance;
          direction = (direction - 2.0 * cos_inside * normal).normalized();
          next = position + flight * direction;
          if (ends_inside(next)) return false;
          continue;
        }
        exit.cos_outside = surface.cos_transmitted;
      } else {
        exit.cos_outside = cos_inside;
      }
      exit.triangle = at.triangle;
      exit.x = position.x();
      exit.y = position.y();
      exit.remaining = flight - at.distance;
      // Light that leaves a convex object is not followed: its direction outside is not needed.
      if (convex()) return true;
      if constexpr (fresnel) {
        direction = refracted(direction, -normal, 1.0 / eta_, cos_inside, exit.cos_outside);
      }
      if (!enter(position, direction, random, epsilon_)) return true;
      // Back inside: a fresh flight from the point of entry.
      flight = -std::log(random.next4()[0]);
      next = position + flight * direction;
    }
    return false;
  }

 private:
  // Whether a flight from inside that ends at `next` in a convex object certainly stays inside:
  // its end lies in the core or in a cell wholly inside (transport/object_boundary.hpp). Not
  // looked up in other objects, where it would cost a cache miss a flight for a query seldom
  // spared; there a flight shorter than its start's clearance stays inside.
  bool ends_inside(const Vec3& next) const { return convex() && interior_.inside(next); }

  // The crossing of a flight of `flight` from inside at `position` along `direction`, as
  // next_facing(false, ...): in a convex object by the walk (t_near is then not needed: the
  // walk finds the facet the ray leaves by, not the one it is on), and by Embree where the walk
  // gives up.
  bool next_exit(const Vec3& position, const Vec3& direction, double t_near, double flight,
                 MeshCrossing& at, double& cos_inside) const {
    if (crossing_ &&
        crossing_->leave(position, direction, at, cos_inside) == ConvexCrossing::Walk::crosses) {
      return at.distance < flight;
    }
    return next_facing(false, position, direction, t_near, flight, at, cos_inside);
  }

  // The next crossing in (t_near, t_far) met from outside (`from_outside`) or from inside, and
  // the cosine of incidence on that side. A facet met from the other side is the one the ray
  // starts on (round-off: the point of entry or of exit), and is passed.
  bool next_facing(bool from_outside, const Vec3& position, const Vec3& direction, double t_near,
                   double t_far, MeshCrossing& at, double& cos_incidence) const {
    while (next_crossing(*tracer_, *mesh_, position, direction, t_near, t_far, at)) {
      cos_incidence = from_outside ? -direction.dot(at.normal) : direction.dot(at.normal);
      if (cos_incidence > 0.0) return true;
      t_near = at.distance + epsilon_;
    }
    return false;
  }

  static constexpr double infinity = std::numeric_limits<double>::infinity();
  const MeshRayTracer* tracer_;
  const TriangleMesh* mesh_;
  double eta_;
  double epsilon_;
  std::shared_ptr<const SurfaceClearance> clearance_;  // shared by the walk's copies
  std::shared_ptr<const ConvexCrossing> crossing_;     // in a convex object only: convex()
  InteriorClearance interior_;                         // the grid's, with the core of a convex one
};

}  // namespace scatterlab
