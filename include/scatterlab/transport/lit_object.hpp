#pragma once
// A lit object: the analytic sphere, run here, or a triangle mesh (the spec's `mesh`, run by
// mesh/lit_mesh.hpp). The lit sphere (Bitterli 2013, §3.2; Vavassori §4.3): a sphere of radius R
// filled with the medium, behind a smooth interface of relative index eta, lit by a directional
// light travelling along +z (the reference Bitterli holds analytic BSSRDFs against) or by a
// pencil beam entering at the lit pole along the inward normal (the searchlight on a curved
// surface). What the run is asked to do, as plain structs validated once, and the run itself.
//
// Tallies, per unit power that meets the sphere: the radiant exitance M(psi) on the surface
// against the angle psi from the lit pole (0, 0, -R), the total power that leaves, the power
// absorbed and the light reflected where it meets the surface; each photon ends in exactly one of
// them, so they sum to 1 photon by photon. Lengths (radius) are in medium.length_unit, mean free
// paths by default; transport runs in mfp (length_units.hpp converts).

#include <array>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/core/triangle_mesh.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/transport/declared_tally.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

enum class ObjectLight {
  directional,  // uniform over the sphere's shadow disk, along +z (Bitterli §3.2)
  pole_beam,    // a pencil beam at the lit pole, along the inward normal +z
  beam,         // a pencil beam from beam_origin along beam_direction, outside the sphere
  sphere,       // a sphere of light (uniform radiance) about light_center: on a mesh only
};

struct LitObjectSpec {
  Medium medium{0.99, 1.0, 0.0, "mfp"};
  double radius = 1.0;  // in medium.length_unit
  double eta = 1.3;     // n_medium / n_outside, in [min_eta, max_eta] (searchlight.hpp)
  ObjectLight light = ObjectLight::directional;
  // The beam (light = beam): from a point outside the sphere (in medium.length_unit) along a
  // direction that meets it; refracted where it meets the surface, its Fresnel reflection exact.
  std::array<double, 3> beam_origin{0.0, 0.0, -2.0};
  std::array<double, 3> beam_direction{0.0, 0.0, 1.0};
  // The sphere of light (light = sphere; in medium.length_unit), clear of the object.
  std::array<double, 3> light_center{0.0, 0.0, -4.0};
  double light_radius = 0.5;
  UniformAxis psi{0.0, std::numbers::pi, 36};  // exit point's angle from the lit pole
  // The exit point's azimuth about z, from +x: one bin for a light symmetric about z (the
  // directional light, the pole beam), more for a beam off the axis.
  UniformAxis azimuth{0.0, 2.0 * std::numbers::pi, 1};
  bool split_by_order = true;  // siblings _unscattered, _single, _multiple
  RunSettings run{1'000'000, 64, 1, 0};
  std::optional<MaterialOrigin> material;  // set when the medium came from a measured table
  // geometry.type = "mesh": a closed triangle mesh (in medium.length_unit) in place of the
  // sphere, whose radius and psi-azimuth grid are then unused. Its exitance is per triangle; the
  // directional light still travels along +z, and a beam meets the mesh where its line does.
  // Run by mesh/lit_mesh.hpp (Embree); run_lit_sphere refuses it.
  std::shared_ptr<const TriangleMesh> mesh;
  std::string mesh_source;  // what the mesh is: the scene's shape and sizes, or its OBJ file
  // [[tally]]: tallies the scene declares beside its own (declared_tally.hpp).
  std::vector<DeclaredTally> declared_tallies = {};

  // Throws InputError naming the first bad field and what it accepts.
  void validate() const;
};

// What shapes the tallies: equal for a run and its resumption (run_settings.hpp).
std::string fingerprint(const LitObjectSpec& spec);

// The engine's problem for this spec: the sphere geometry, the light, the declared tallies. For a
// mesh, the tallies and the run (GeometryKind::mesh): its geometry and light are render's.
TransportProblem transport_problem(const LitObjectSpec& spec);

// Runs the spec on the transport engine; only the root rank gets tallies.
TransportOutput run_lit_sphere(const LitObjectSpec& spec, const ProgressCallback& progress = {},
                               const RunControl& control = {});

std::string to_string(ObjectLight light);

}  // namespace scatterlab
