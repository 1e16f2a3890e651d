#pragma once
// What one simulation is asked to do, as plain structs validated once (docs/architecture.md, "From
// a scene to a file"). Lengths (grid, escape radius) are in medium.length_unit: mean free paths by
// default. Transport runs in mfp; transport/length_units.hpp converts at its boundary.

#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/transport/declared_tally.hpp"
#include "scatterlab/transport/estimator.hpp"
#include "scatterlab/transport/run_settings.hpp"

namespace scatterlab {

enum class SourceKind {
  pencil_beam,  // at the origin, travelling along +z (Vavassori §4.1)
  point,        // isotropic point source at the origin (d'Eon & Irving 2011 fluence curves)
};

// The paper's grid (Vavassori §4.1): r in [0, 1.5], z in [-1, 3] mfp, theta in [0, pi],
// phi in [0, 2 pi] measured from the outward radial direction e_r.
struct Grid {
  UniformAxis r{0.0, 1.5, 15};
  UniformAxis z{-1.0, 3.0, 40};
  UniformAxis theta{0.0, std::numbers::pi, 18};
  UniformAxis phi{0.0, 2.0 * std::numbers::pi, 36};  // max is pi when fold_phi
  bool fold_phi = false;                             // L(phi) = L(-phi): fold onto [0, pi]
  UniformAxis rho{0.0, 10.0, 200};                   // spherical shells (point source)

  // Folding halves the phi axis: [0, pi] folded, [0, 2 pi] not.
  void set_fold_phi(bool fold) {
    fold_phi = fold;
    phi.max = fold ? std::numbers::pi : 2.0 * std::numbers::pi;
  }
};

// Tallies that were not asked for are not allocated.
struct TallyRequest {
  bool radiance = true;            // L(r, z, theta, phi)
  bool fluence = true;             // phi(r, z)
  bool flux = true;                // E(r, z) = (E_r, E_z)
  bool fluence_spherical = false;  // phi(rho); point source only
  bool split_by_order = false;     // siblings _unscattered, _single, _multiple
  Estimator estimator = Estimator::collision;
};

struct InfiniteMediumSpec {
  Medium medium;
  SourceKind source = SourceKind::pencil_beam;
  Grid grid;
  TallyRequest tallies;
  RunSettings run;
  std::optional<MaterialOrigin> material;  // set when the medium came from a measured table
  // [[tally]]: tallies the scene declares beside its own (declared_tally.hpp).
  std::vector<DeclaredTally> declared_tallies = {};

  // Sets the source and its natural default tallies: the point source's is the fluence on
  // spherical shells (d'Eon & Irving 2011); the beam has no spherical symmetry.
  void set_source(SourceKind kind) {
    source = kind;
    tallies.fluence_spherical = kind == SourceKind::point;
  }

  // Throws InputError naming the first bad field and what it accepts.
  void validate() const;
};

// 16 hex digits naming everything that determines the tallies bit for bit: medium, source, grid,
// tallies, photons, batches, seed and escape radius; not threads or ranks, which never change a
// result. Checkpoints and sweeps use it to recognise the same run.
std::string fingerprint(const InfiniteMediumSpec& spec);

std::string to_string(SourceKind source);

}  // namespace scatterlab
