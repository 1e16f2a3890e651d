#pragma once
// What the transport engine runs: one medium in one geometry, a source, the declared tallies
// and how many photons. Every command's spec (the infinite medium's InfiniteMediumSpec, the
// searchlight's HalfSpaceSpec) becomes one of these; the engine picks the one compiled kernel
// it needs (engine.hpp). Lengths are in mean free paths (sigma_t = 1), but in a slab, whose layers
// each have their own sigma_t, in the spec's length unit.

#include <cstdint>
#include <string>
#include <vector>

#include "scatterlab/tally/tally_axes.hpp"
#include "scatterlab/tally/tally_declaration.hpp"
#include "scatterlab/tally/units.hpp"
#include "scatterlab/transport/estimator.hpp"
#include "scatterlab/transport/run_settings.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/source.hpp"
#include "scatterlab/transport/weighting.hpp"

namespace scatterlab {

enum class GeometryKind {
  infinite,    // no surface (infinite_medium.hpp)
  half_space,  // z > 0 behind a smooth interface at z = 0 (half_space.hpp)
  sphere,      // |x| < radius behind a smooth interface (sphere.hpp)
  slab,        // layers from z = 0 down, between two ambient media (slab.hpp)
  mesh,        // a closed triangle mesh: its geometry and light come from outside this module
               // (kernel.hpp; mesh/lit_mesh.hpp, with Embree)
};

struct TransportProblem {
  double albedo = 0.5;
  double g = 0.0;  // Henyey-Greenstein mean cosine; 0 samples isotropically
  GeometryKind geometry = GeometryKind::infinite;
  double eta = 1.0;     // n_medium / n_outside at the surface, where there is one
  double radius = 1.0;  // of the sphere, mfp
  // The slab's layers, top down (albedo, g and eta above are unused there), and the indices of
  // the media above and below it.
  std::vector<SlabLayer> layers;
  double n_above = 1.0, n_below = 1.0;
  Weighting weighting = Weighting::analog;  // implicit capture only in a slab
  Source source;
  TallyAxes axes;
  std::vector<TallyDeclaration> tallies;
  bool split_by_order = false;
  Estimator estimator = Estimator::collision;  // of the volume tallies
  // The power each photon carries, per unit incident power: what entered through the surface.
  double photon_power = 1.0;
  // The unit the tallies are reported in, and how many of the lengths above make one of it
  // (length_units.hpp): the spec's, which TallyBook::finish converts to by each tally's units.
  ReportedLength length;
  RunSettings run;
  // The spec's fields that size the tallies, as a memory error names them (engine.hpp).
  std::string size_fields = "tallies";
};

}  // namespace scatterlab
