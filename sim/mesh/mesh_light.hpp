#pragma once
// The lights of an object bounded by a triangle mesh (mesh_boundary.hpp), as the transport
// engine launches them (transport/kernel.hpp):
//   beam         a pencil beam from `origin` along `direction`, outside the object;
//   directional  parallel light along `direction` over the whole object (Bitterli 2013, §3.2,
//                on a sphere): photons start uniformly over the disc, facing the light, of the
//                sphere that bounds the mesh, and those whose line misses the mesh are drawn
//                again. Each photon therefore stands for an equal share of the power that
//                meets the object, the normalisation of the lit sphere (source.hpp), whatever
//                the object's shadow. On a convex object, whose facing facets tile its shadow
//                once, the same photons start on a facet drawn in proportion to its shadow
//                (area times cosine of incidence), uniformly over it: no line to trace, none
//                drawn again;
//   sphere       a sphere of light of uniform radiance about `origin`, of radius `radius`
//                (Vavassori §4.3, the light over the milk sphere): photons leave its surface
//                uniformly, each along a cosine-distributed direction about the outward normal
//                (a uniform radiance's emission), and those whose line misses the object are drawn
//                again, so they too stand for equal shares of the power that meets it. The light
//                is no obstacle to light that leaves the object.
// Both meet the surface as every light outside does (MeshBoundary::enter): reflected with
// probability F, and followed on, or refracted in. launch is false for a photon that is
// reflected off the object and never enters.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "mesh_boundary.hpp"
#include "scatterlab/core/alias_table.hpp"
#include "scatterlab/core/azimuth.hpp"
#include "scatterlab/core/frame.hpp"
#include "scatterlab/core/random.hpp"
#include "scatterlab/transport/object_boundary.hpp"

namespace scatterlab {

template <bool fresnel>
class MeshLight {
 public:
  enum class Kind { beam, directional, sphere };

  // `center` and `radius`: a sphere holding the mesh (directional light); the light's own
  // sphere about `origin` (sphere).
  MeshLight(const MeshBoundary<fresnel>& boundary, Kind kind, const Vec3& origin,
            const Vec3& direction, const Vec3& center, double radius)
      : boundary_(boundary),
        kind_(kind),
        origin_(origin),
        direction_(direction.normalized()),
        across_(direction_),
        center_(center),
        radius_(radius) {
    // The beam meets the mesh first at the same point for every photon.
    if (kind_ == Kind::beam) {
      beam_meets_ = boundary_.first_entry(origin_, direction_, 0.0, beam_entry_, beam_cos_);
    }
    if (kind_ == Kind::directional && boundary_.convex()) {
      const TriangleMesh& mesh = boundary_.mesh();
      std::vector<double> shadow(mesh.triangle_count());
      for (std::uint32_t t = 0; t < shadow.size(); ++t) {
        shadow[t] = mesh.area(t) * std::max(-boundary_.facet_normal(t).dot(direction_), 0.0);
      }
      lit_facets_.emplace(shadow);
    }
  }

  bool launch(PhotonRandom& random, Vec3& start, Vec3& heading) const {
    if (kind_ == Kind::beam) {
      start = origin_;
      heading = direction_;
      return beam_meets_ &&
             boundary_.enter_at(beam_entry_, beam_cos_, fresnel ? random.next4()[0] : 0.0, start,
                                heading, random);
    }
    if (kind_ == Kind::sphere) {
      for (;;) {
        const auto u = random.next4();
        const Vec3 normal = isotropic_direction(u[0], u[1]);
        // Lambert's law: cos theta = sqrt(u) about the normal.
        const double cos_theta = std::sqrt(u[2]), sin_theta = std::sqrt(1.0 - u[2]);
        const UnitCircle phi = azimuth(u[3]);
        start = origin_ + radius_ * normal;
        heading = Frame(normal).to_world(sin_theta * phi.cos, sin_theta * phi.sin, cos_theta);
        bool met = false;  // a line that misses the object is drawn again
        if (boundary_.enter(start, heading, random, 0.0, &met)) return true;
        if (met) return false;
      }
    }
    if (lit_facets_) {
      const auto u = random.next4();
      MeshCrossing at;
      at.triangle = lit_facets_->draw(u[0]);
      const TriangleMesh& mesh = boundary_.mesh();
      const Vec3 &a = mesh.vertex(at.triangle, 0), &b = mesh.vertex(at.triangle, 1),
                 &c = mesh.vertex(at.triangle, 2);
      // Uniform over the triangle (Osada et al. 2002, "Shape distributions", ACM TOG 21(4),
      // §4.2, eq. 1).
      const double root = std::sqrt(u[1]);
      at.point = (1.0 - root) * a + root * (1.0 - u[2]) * b + root * u[2] * c;
      at.normal = boundary_.facet_normal(at.triangle);
      heading = direction_;
      // The photon's one Philox call draws its Fresnel choice too.
      return boundary_.enter_at(at, -at.normal.dot(direction_), u[3], start, heading, random);
    }
    // Uniform over the disc: r = R sqrt(u), on a plane a radius behind the centre. A closed mesh
    // of positive volume has a shadow of positive area, so the draw ends (a needle 1e-3 of the
    // disc takes a thousand tries).
    for (;;) {
      const auto u = random.next4();
      const UnitCircle phi = azimuth(u[1]);
      const double r = radius_ * std::sqrt(u[0]);
      start =
          center_ - 1.5 * radius_ * direction_ + across_.to_world(r * phi.cos, r * phi.sin, 0.0);
      heading = direction_;
      bool met = false;  // a line that misses the object is drawn again
      if (boundary_.enter(start, heading, random, 0.0, &met)) return true;
      if (met) return false;
    }
  }

 private:
  const MeshBoundary<fresnel>& boundary_;
  Kind kind_;
  Vec3 origin_, direction_;
  Frame across_;  // tangent and bitangent span the disc
  Vec3 center_;
  double radius_;
  std::optional<AliasTable> lit_facets_;  // directional light on a convex object
  bool beam_meets_ = false;               // the beam's first crossing, and its cosine of incidence
  MeshCrossing beam_entry_;
  double beam_cos_ = 0.0;
};

// The object and its light as the lane walk runs them (transport/object_boundary.hpp), when
// the object is convex; none otherwise. Both outlive what it returns.
template <bool fresnel>
std::optional<ObjectBoundary> object_boundary(const MeshBoundary<fresnel>& boundary,
                                              const MeshLight<fresnel>& light) {
  if (!boundary.convex()) return std::nullopt;
  return ObjectBoundary(
      &boundary,
      [](const void* object, Vec3& position, Vec3& direction, Vec3& next, double flight,
         PhotonRandom& random, SurfaceExit& exit) {
        return static_cast<const MeshBoundary<fresnel>*>(object)->meets_surface(
            position, direction, next, flight, random, exit);
      },
      &light,
      [](const void* object_light, PhotonRandom& random, Vec3& start, Vec3& heading) {
        return static_cast<const MeshLight<fresnel>*>(object_light)->launch(random, start, heading);
      },
      boundary.interior());
}

}  // namespace scatterlab
