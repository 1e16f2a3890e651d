#include "scatterlab/mesh/lit_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "convex_mesh.hpp"
#include "mesh_boundary.hpp"
#include "mesh_light.hpp"
#include "scatterlab/core/error.hpp"
#include "scatterlab/mesh/mesh_checks.hpp"
#include "scatterlab/mesh/mesh_ray_tracer.hpp"
#include "scatterlab/transport/kernel.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

Vec3 vec3(const std::array<double, 3>& a) {
  return Vec3(a[0], a[1], a[2]);
}

// A direction of no special alignment, so that a parity ray does not run along an edge.
const Vec3 kProbe = Vec3(0.5773, 0.6123, 0.5407).normalized();

// The distance from p to the triangle abc: to its closest point, found by the Voronoi region of
// the triangle p falls in (Ericson, Real-Time Collision Detection, 2005, §5.1.5).
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return (p - a).norm();  // corner a
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return (p - b).norm();  // corner b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (p - (a + d1 / (d1 - d3) * ab)).norm();  // ab
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return (p - c).norm();  // corner c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (p - (a + d2 / (d2 - d6) * ac)).norm();  // ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {  // edge bc
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denominator = 1.0 / (va + vb + vc);  // inside the face
  return (p - (a + ab * (vb * denominator) + ac * (vc * denominator))).norm();
}

}  // namespace

void check_lit_mesh(const LitObjectSpec& spec) {
  const TriangleMesh& mesh = *spec.mesh;
  require_closed_mesh(mesh);
  require_enclosed_volume(mesh);
  require_no_self_intersection(mesh);
  // Light that leaves an object that is not convex may enter it again, after crossing air the
  // walk does not time (and its path resumes from a fresh flight): time needs a convex mesh.
  for (std::size_t i = 0; i < spec.declared_tallies.size(); ++i) {
    if (spec.declared_tallies[i].filter(Coordinate::t) != nullptr && !bounds_convex_solid(mesh)) {
      throw InputError(fmt::format("tally[{}].filters.t", i + 1),
                       "is asked on a mesh that is not convex",
                       "a convex mesh: light that leaves an object that is not convex and enters "
                       "it again crosses air whose time of flight the walk does not keep");
    }
  }
  if (spec.light != ObjectLight::beam && spec.light != ObjectLight::sphere) return;
  const MeshRayTracer tracer(mesh);
  if (spec.light == ObjectLight::sphere) {
    const Vec3 center = vec3(spec.light_center);
    if (tracer.count_crossings(center, kProbe) % 2 == 1) {
      throw InputError("source.position", "is inside the mesh", "a point outside the object");
    }
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const double clearance =
          distance_to_triangle(center, mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2));
      if (clearance <= spec.light_radius) {
        throw InputError("source.radius",
                         fmt::format("makes the sphere of light cut into the object: triangle {} "
                                     "is {:g} from source.position",
                                     t, clearance),
                         "a radius less than the light's distance to the object's surface");
      }
    }
    return;
  }
  const Vec3 origin = vec3(spec.beam_origin);
  if (tracer.count_crossings(origin, kProbe) % 2 == 1) {
    throw InputError("source.origin", "is inside the mesh", "a point outside the object");
  }
  MeshHit hit;
  if (!tracer.intersect(origin, vec3(spec.beam_direction).normalized(), 0.0,
                        std::numeric_limits<double>::infinity(), hit)) {
    throw InputError("source.direction", "misses the mesh from source.origin",
                     "a direction from source.origin that meets the object");
  }
}

TransportOutput run_lit_mesh(const LitObjectSpec& spec, const ProgressCallback& progress,
                             const RunControl& control) {
  spec.validate();
  check_lit_mesh(spec);
  // Transport runs in mfp (length_units.hpp): the mesh and the beam's origin are scaled to it.
  const double scale = mfp_per_length_unit(spec.medium);
  TriangleMesh mesh = *spec.mesh;
  for (Vec3& p : mesh.positions) p *= scale;
  const MeshRayTracer tracer(mesh);
  const Vec3 center = mesh.bounds().center();
  double radius = 0.0;
  for (const Vec3& p : mesh.positions) radius = std::max(radius, (p - center).norm());
  radius *= 1.0 + 1e-6;  // the disc's rim clears every vertex
  const bool beam = spec.light == ObjectLight::beam;
  const bool sphere = spec.light == ObjectLight::sphere;
  Vec3 origin = Vec3::Zero(), direction = Vec3::UnitZ();
  if (beam) {
    origin = vec3(spec.beam_origin) * scale;
    direction = vec3(spec.beam_direction).normalized();
  } else if (sphere) {
    origin = vec3(spec.light_center) * scale;
  }
  const TransportProblem problem = transport_problem(spec);

  const auto run = [&]<bool fresnel>() {
    using Light = MeshLight<fresnel>;
    const MeshBoundary<fresnel> boundary(tracer, mesh, spec.eta);
    const typename Light::Kind kind =
        beam ? Light::Kind::beam : (sphere ? Light::Kind::sphere : Light::Kind::directional);
    const Light light(boundary, kind, origin, direction, center,
                      sphere ? spec.light_radius * scale : radius);
    return transport(problem, boundary, light, progress, control);
  };
  return spec.eta == 1.0 ? run.template operator()<false>() : run.template operator()<true>();
}

}  // namespace scatterlab
