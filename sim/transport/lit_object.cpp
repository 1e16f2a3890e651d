#include "scatterlab/transport/lit_object.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/transport/length_units.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {

namespace {

std::string got(double value) {
  return fmt::format("got {}", value);
}

struct BeamEntry {
  Vec3 point, direction;
  double cos_incidence;
};

// Where a beam from outside meets the sphere of radius R about the origin, and at what cosine of
// incidence; nullopt when it misses (or only grazes) it. The pole beam meets (0, 0, -R) along
// the normal.
std::optional<BeamEntry> beam_entry(const LitObjectSpec& spec, double radius_mfp) {
  if (spec.light == ObjectLight::pole_beam) {
    return BeamEntry{Vec3(0.0, 0.0, -radius_mfp), Vec3::UnitZ(), 1.0};
  }
  const double mfp_per_unit = mfp_per_length_unit(spec.medium);
  const Vec3 origin =
      Vec3(spec.beam_origin[0], spec.beam_origin[1], spec.beam_origin[2]) * mfp_per_unit;
  const Vec3 direction =
      Vec3(spec.beam_direction[0], spec.beam_direction[1], spec.beam_direction[2]).normalized();
  // |o + t w|^2 = R^2: t^2 + 2 b t + c = 0, the nearer root for an origin outside.
  const double b = origin.dot(direction), c = origin.squaredNorm() - radius_mfp * radius_mfp;
  const double discriminant = b * b - c;
  if (!(discriminant > 0.0) || !(b < 0.0)) return std::nullopt;
  const Vec3 point = origin + (-b - std::sqrt(discriminant)) * direction;
  return BeamEntry{point, direction, std::clamp(-direction.dot(point) / radius_mfp, 0.0, 1.0)};
}

// A mesh's triangle areas in mfp^2, as it is transported.
std::vector<double> triangle_areas_mfp(const LitObjectSpec& spec) {
  const double scale = mfp_per_length_unit(spec.medium);
  std::vector<double> areas(spec.mesh->triangle_count());
  for (std::size_t t = 0; t < areas.size(); ++t) areas[t] = spec.mesh->area(t) * scale * scale;
  return areas;
}

// What the object gives its declared tallies: its surface, with the sphere's radius or the
// mesh's areas in the walk's units.
DeclaredTallyFrame object_frame(const LitObjectSpec& spec) {
  DeclaredTallyFrame frame =
      homogeneous_frame(spec.mesh ? "mesh" : "sphere", spec.medium, spec.eta);
  if (spec.mesh) {
    frame.triangle_areas = triangle_areas_mfp(spec);
  } else {
    frame.radius = spec.radius * mfp_per_length_unit(spec.medium);
  }
  return frame;
}

// The object's tallies, each declared once, all but the light reflected at entry by order (its
// surface's in `frame`, walk units); then the scene's own.
std::vector<TallyDeclaration> declare_tallies(const LitObjectSpec& spec,
                                              const DeclaredTallyFrame& frame,
                                              double beam_reflectance) {
  std::vector<TallyDeclaration> tallies;
  if (spec.mesh) {
    tallies.push_back({"exitance",
                       Score::exitance,
                       {triangle_filter(frame.triangle_areas)},
                       Units{1, -2},
                       "radiant exitance M on the mesh: power leaving the object for good "
                       "through each triangle per unit of its area",
                       true});
  } else {
    tallies.push_back({"exitance",
                       Score::exitance,
                       {sphere_patch_filter(spec.psi, spec.azimuth, frame.radius)},
                       Units{1, -2},
                       "radiant exitance M(psi, azimuth) on the sphere: power leaving per unit "
                       "area of the patch at angle psi from the lit pole (0, 0, -R) and azimuth "
                       "about z from +x, patch average",
                       true});
  }
  const char* object = spec.mesh ? "object" : "sphere";
  tallies.push_back({"exited",
                     Score::exitance,
                     {},
                     Units{},
                     fmt::format("total power leaving the {} after it entered (any point, any "
                                 "angle)",
                                 object),
                     true});
  tallies.push_back({"absorbed",
                     Score::absorbed,
                     {},
                     Units{},
                     fmt::format("power absorbed in the {}", object),
                     true});
  // On a mesh even a beam's reflection is counted photon by photon: light reflected off one part
  // of a shape that is not convex can enter another.
  if (spec.light == ObjectLight::directional || spec.mesh) {
    tallies.push_back({"reflected_at_entry",
                       Score::entry_reflectance,
                       {},
                       Units{},
                       fmt::format("light reflected where it meets the {} (Fresnel, each "
                                   "photon's own angle of incidence) that never enters",
                                   object)});
  } else {
    tallies.push_back({"reflected_at_entry",
                       Score::exact,
                       {},
                       Units{},
                       "Fresnel reflection of the beam where it meets the sphere (exact: no "
                       "standard error)",
                       false,
                       beam_reflectance});
  }
  for (TallyDeclaration& d : declare_chained_tallies(spec.declared_tallies, frame, tallies)) {
    tallies.push_back(std::move(d));
  }
  return tallies;
}

}  // namespace

std::string to_string(ObjectLight light) {
  switch (light) {
    case ObjectLight::directional:
      return "directional";
    case ObjectLight::pole_beam:
      return "pole_beam";
    case ObjectLight::beam:
      return "beam";
    case ObjectLight::sphere:
      return "sphere";
  }
  return "unknown";
}

namespace {

// A sphere about the origin that holds the mesh, in mfp (its farthest vertex).
double bounding_radius_mfp(const LitObjectSpec& spec) {
  double farthest = 0.0;
  for (const Vec3& p : spec.mesh->positions) farthest = std::max(farthest, p.norm());
  return farthest * mfp_per_length_unit(spec.medium);
}

void check_beam(const LitObjectSpec& spec) {
  for (const double x : spec.beam_origin) {
    if (!std::isfinite(x)) {
      throw InputError("source.origin", "is not finite", "three finite numbers [x, y, z]");
    }
  }
  const double length =
      std::hypot(spec.beam_direction[0], spec.beam_direction[1], spec.beam_direction[2]);
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InputError("source.direction", "is zero or not finite",
                     "three finite numbers [x, y, z], not all 0");
  }
}

// The mesh's own checks (closed, outside the beam's origin, met by the beam) need its ray
// tracer: mesh/lit_mesh.hpp makes them.
void validate_mesh_spec(const LitObjectSpec& spec) {
  if (spec.light == ObjectLight::pole_beam) {
    throw InputError("source.type", "\"pole_beam\" on a mesh, which has no pole",
                     "\"directional\", \"beam\" (with source.origin and source.direction) or "
                     "\"sphere\" (with source.position and source.radius)");
  }
  if (spec.mesh->triangle_count() == 0) {
    throw InputError("mesh", "has no triangles", "a closed triangle mesh");
  }
  spec.mesh->validate();
  if (spec.light == ObjectLight::beam) check_beam(spec);
  if (spec.light == ObjectLight::sphere) {
    for (const double x : spec.light_center) {
      if (!std::isfinite(x)) {
        throw InputError("source.position", "is not finite", "three finite numbers [x, y, z]");
      }
    }
    if (!(spec.light_radius > 0.0) || !std::isfinite(spec.light_radius)) {
      throw InputError("source.radius", got(spec.light_radius),
                       "a finite number > 0 (in medium.length_unit)");
    }
  }
  const double radius_mfp = bounding_radius_mfp(spec);
  if (!(radius_mfp >= 1e-6 && radius_mfp <= 1e6)) {
    throw InputError("mesh", fmt::format("reaches {} mfp from the origin", radius_mfp),
                     "a mesh within 1e-6 to 1e6 mean free paths of the origin");
  }
  check_run_settings(spec.run);
  check_run_length(spec.run, spec.medium.albedo, radius_mfp);
}

}  // namespace

void LitObjectSpec::validate() const {
  medium.validate();
  check_length_unit(medium);
  if (!(eta >= min_eta && eta <= max_eta)) {
    throw InputError("geometry.eta", got(eta),
                     "a number in [0.1, 10] (n_medium / n_outside; 1 for no interface)");
  }
  if (mesh) {
    validate_mesh_spec(*this);
    check_declared_tallies(declared_tallies, object_frame(*this));
    return;
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError("geometry.radius", got(radius), "a finite number > 0 (in medium.length_unit)");
  }
  const double radius_mfp = radius * mfp_per_length_unit(medium);
  if (!(radius_mfp >= 1e-6 && radius_mfp <= 1e6)) {
    throw InputError("geometry.radius", fmt::format("is {} mfp", radius_mfp),
                     "a radius of 1e-6 to 1e6 mean free paths");
  }
  if (light == ObjectLight::sphere) {
    throw InputError("source.type", "\"sphere\" on the analytic sphere",
                     "\"directional\", \"pole_beam\" or \"beam\"; a sphere of light shines on "
                     "a mesh (geometry.type = \"mesh\", e.g. [mesh] shape = \"sphere\")");
  }
  if (psi.min != 0.0 || std::abs(psi.max - std::numbers::pi) > 1e-12) {
    throw InputError("grid.psi", fmt::format("spans [{}, {}]", psi.min, psi.max),
                     "[0, pi]: the angle from the lit pole");
  }
  if (psi.bins < 1 || psi.bins > 100'000) {
    throw InputError("grid.psi.bins", fmt::format("got {}", psi.bins), "an integer in [1, 100000]");
  }
  if (azimuth.min != 0.0 || std::abs(azimuth.max - 2.0 * std::numbers::pi) > 1e-12) {
    throw InputError("grid.azimuth", fmt::format("spans [{}, {}]", azimuth.min, azimuth.max),
                     "[0, 2 pi]: the azimuth about z");
  }
  if (azimuth.bins < 1 || static_cast<double>(azimuth.bins) * psi.bins > 1e7) {
    throw InputError("grid.azimuth.bins", fmt::format("got {}", azimuth.bins),
                     "an integer >= 1, with grid.psi.bins x grid.azimuth.bins at most 1e7");
  }
  if (light == ObjectLight::beam) {
    check_beam(*this);
    const double origin_mfp =
        std::hypot(beam_origin[0], beam_origin[1], beam_origin[2]) * mfp_per_length_unit(medium);
    if (!(origin_mfp > radius_mfp)) {
      throw InputError("source.origin", "is not outside the sphere",
                       "a point farther than geometry.radius from the centre");
    }
    if (!beam_entry(*this, radius_mfp)) {
      throw InputError("source.direction", "misses the sphere from source.origin",
                       "a direction from source.origin that meets the sphere");
    }
  }
  check_run_settings(run);
  // Every walk ends inside the sphere: by absorption, or by leaving it after about R^2 events.
  check_run_length(run, medium.albedo, radius_mfp);
  check_declared_tallies(declared_tallies, object_frame(*this));
}

namespace {

// Every vertex and triangle of a mesh, exactly.
std::string mesh_fingerprint(const TriangleMesh& mesh) {
  std::string text = fmt::format("|mesh {} {}", mesh.positions.size(), mesh.triangle_count());
  for (const Vec3& p : mesh.positions) text += fmt::format(" {:a} {:a} {:a}", p.x(), p.y(), p.z());
  for (const auto& t : mesh.triangles) text += fmt::format(" {} {} {}", t[0], t[1], t[2]);
  return text;
}

}  // namespace

std::string fingerprint(const LitObjectSpec& spec) {
  const Medium& m = spec.medium;
  return fingerprint_of(
      fmt::format("lit_sphere|medium {:a} {:a} {:a} {}|radius {:a}|eta "
                  "{:a}|light {}|beam {:a} {:a} {:a} {:a} "
                  "{:a} {:a}|psi {:a},{:a},{}|azimuth {}|split {}|run {} {} {}",
                  m.albedo, m.g, m.sigma_t, m.length_unit, spec.radius, spec.eta,
                  to_string(spec.light), spec.beam_origin[0], spec.beam_origin[1],
                  spec.beam_origin[2], spec.beam_direction[0], spec.beam_direction[1],
                  spec.beam_direction[2], spec.psi.min, spec.psi.max, spec.psi.bins,
                  spec.azimuth.bins, spec.split_by_order, spec.run.photons, spec.run.batches,
                  spec.run.seed) +
      (spec.light == ObjectLight::sphere
           ? fmt::format("|light sphere {:a} {:a} {:a} {:a}", spec.light_center[0],
                         spec.light_center[1], spec.light_center[2], spec.light_radius)
           : std::string()) +
      (spec.mesh ? mesh_fingerprint(*spec.mesh) : std::string()) +
      fingerprint_text(spec.declared_tallies));
}

TransportProblem transport_problem(const LitObjectSpec& spec) {
  const double radius = spec.radius * mfp_per_length_unit(spec.medium);
  TransportProblem problem;
  problem.albedo = spec.medium.albedo;
  problem.g = spec.medium.g;
  problem.eta = spec.eta;
  problem.split_by_order = spec.split_by_order;
  problem.estimator = Estimator::collision;
  problem.run = spec.run;
  problem.length = reported_length(spec.medium);  // back from mfp
  problem.run.escape_radius = std::numeric_limits<double>::infinity();
  if (spec.mesh) {
    problem.geometry = GeometryKind::mesh;
    // A closed mesh keeps every photon until it leaves; should round-off let one slip out
    // unnoticed, it ends far away (uncounted, so that the energy balance shows it) rather than
    // wander for ever.
    problem.run.escape_radius = 1e3 * (1.0 + bounding_radius_mfp(spec));
    problem.tallies = declare_tallies(spec, object_frame(spec), 0.0);
    problem.size_fields = "the mesh's triangles, run.threads";
    return problem;
  }
  problem.geometry = GeometryKind::sphere;
  problem.radius = radius;
  // A beam is refracted where it meets the sphere, F of its incidence reflected, and 1 - F enters
  // and carries every other tally (as the searchlight's beam does); beyond the critical angle of
  // an eta < 1 sphere nothing enters, and every tally is scaled by the transmitted power, 0. The
  // directional light's reflection depends on where each photon meets the sphere, so it is
  // counted photon by photon.
  double beam_reflectance = 0.0;
  if (spec.light == ObjectLight::directional) {
    problem.source.kind = Source::Kind::sphere_light;
    problem.source.sphere_radius = radius;
    problem.source.eta = spec.eta;
  } else {
    const std::optional<BeamEntry> entry = beam_entry(spec, radius);
    if (!entry) throw std::invalid_argument("transport_problem: the beam misses the sphere");
    problem.source.kind = Source::Kind::beam;
    problem.source.position = entry->point;
    problem.source.direction = entry->direction;
    refract(entry->direction, entry->point / radius, spec.eta, problem.source.direction);
    beam_reflectance = fresnel_dielectric_reflectance(entry->cos_incidence, spec.eta);
    problem.photon_power = 1.0 - beam_reflectance;
  }
  problem.axes.psi = spec.psi;
  problem.axes.azimuth = spec.azimuth;
  problem.tallies = declare_tallies(spec, object_frame(spec), beam_reflectance);
  problem.size_fields = "grid.psi.bins x grid.azimuth.bins, run.threads";
  return problem;
}

TransportOutput run_lit_sphere(const LitObjectSpec& spec, const ProgressCallback& progress,
                               const RunControl& control) {
  spec.validate();
  if (spec.mesh) throw std::invalid_argument("run_lit_sphere: a mesh runs with run_lit_mesh");
  return transport(transport_problem(spec), progress, control);
}

}  // namespace scatterlab
