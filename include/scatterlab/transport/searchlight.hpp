#pragma once
// The searchlight problem (Bitterli 2013, §2.3, Fig. 2.3; Chandrasekhar 1958): a pencil beam
// strikes a semi-infinite homogeneous medium z > 0 at the origin. What the run is asked to do,
// as plain structs validated once, and the run itself.
//
// Lengths (grid, escape radius) are in medium.length_unit, mean free paths by default (sigma_t =
// 1); transport runs in mfp (transport/length_units.hpp converts). Every tally is per unit incident
// power: the specular reflection at entry is reported apart and the transmitted power 1 - F enters.

#include <numbers>
#include <optional>
#include <string>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/transport/declared_tally.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

// Bins of the half-space tallies. The defaults reach ~10 mfp, where R_d(r) of an albedo-0.99
// medium has fallen by about four decades: enough for the log plots that compare models.
struct HalfSpaceGrid {
  UniformAxis r{0.0, 10.0, 200};  // distance from the entry point
  UniformAxis z{0.0, 10.0, 100};  // depth below the surface
  UniformAxis theta_o{0.0, 0.5 * std::numbers::pi,
                      18};  // exit angle from the outward normal, outside
  // The surface about the entry point, for the exitance map M(x, y) (tallies.exitance_map): the
  // beam arrives in the x-z plane, so an oblique beam's halo is off centre along +x.
  UniformAxis x{-5.0, 5.0, 100};
  UniformAxis y{-5.0, 5.0, 100};
};

struct HalfSpaceTallies {
  // phi(r, z) by the collision estimator costs a bin lookup per event; the surface tallies
  // (R_d(r), exitant radiance, totals) cost one per exit and are always on.
  bool fluence = true;
  // M(x, y) on grid.x x grid.y: what an oblique beam's halo looks like from above (Vavassori
  // §4.3, Fig. 4.11), which the radial tallies average away. One bin lookup per exit.
  bool exitance_map = false;
};

// The relative indices a searchlight accepts (HalfSpaceSpec::validate).
inline constexpr double min_eta = 0.1;
inline constexpr double max_eta = 10.0;

struct HalfSpaceSpec {
  // Defaults: a nearly conservative isotropic medium (albedo 0.99, g = 0), the regime the
  // diffusion models are built for, behind the interface index 1.3 that Jensen et al. 2001 use
  // for all their measured materials.
  Medium medium{0.99, 1.0, 0.0, "mfp"};
  double eta = 1.3;            // relative index n_medium / n_outside, in [min_eta, max_eta]
  double incidence_deg = 0.0;  // angle of the beam from the inward normal, in [0, 90)
  HalfSpaceGrid grid;
  HalfSpaceTallies tallies;
  RunSettings run{10'000'000, 64, 1, 0};
  std::optional<MaterialOrigin> material;  // set when the medium came from a measured table
  // [[tally]]: tallies the scene declares beside its own (declared_tally.hpp).
  std::vector<DeclaredTally> declared_tallies = {};

  // Throws InputError naming the first bad field (CLI flag names) and what it accepts.
  void validate() const;
};

// What shapes the tallies (medium, interface, beam, grid, tallies, run): equal for a run and its
// resumption, different for any other run (run_settings.hpp, fingerprint_of).
std::string fingerprint(const HalfSpaceSpec& spec);

// The engine's problem for this spec: the half-space geometry, the refracted beam, the declared
// tallies (per unit incident power: scaled by the power that entered) and the run.
TransportProblem transport_problem(const HalfSpaceSpec& spec);

// Runs the spec on the transport engine. Bitwise identical for any number of threads and ranks, and
// when resumed (batch_runner.hpp); `control` carries the ranks, checkpoints and stop requests. Only
// the root rank gets tallies.
TransportOutput run_half_space(const HalfSpaceSpec& spec, const ProgressCallback& progress = {},
                               const RunControl& control = {});

}  // namespace scatterlab
