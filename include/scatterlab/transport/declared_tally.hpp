#pragma once
// Tallies a scene declares ([[tally]] in a scene file, io/scene.hpp): a score at the filters a
// user names, beside the geometry's own tallies. The filters bin each event themselves (the
// Scorer's chain, tally/scorer.hpp), so any of them works on any score where the pair makes sense:
//
//   score          its event                                   filters
//   exitance       a photon leaves through the lit surface      x, y, r, theta_o, t, order
//   transmittance  a photon leaves a slab through its far side  x, y, r, theta_o, t, order
//   fluence        a collision (the collision estimator)        x, y, r, z, rho, t, order
//   absorbed       a photon's weight is absorbed                x, y, r, z, rho, t, order, layer
//
// x and y are the event's position (of an exit point on the surface, about the entry point; the
// beam arrives in the x-z plane), r the distance from the beam axis, z the depth, rho the
// distance from the source (the origin: a point source's fluence on shells), all in the scene's
// length unit; theta_o the exit angle from the outward normal,
// outside, per steradian; t the time of flight in seconds since the light entered the medium:
// the path travelled times the group index over c (a slab's layers each at their own index n);
// order the number of scatterings, the last bin holding its order and more; layer a slab's layer,
// top down (layer = true: a bin per layer). A tally against t is
// the response to a unit impulse, per joule incident; one without t is per watt, as the
// geometry's own tallies are. Its cells are row-major in the order of the table below, whatever
// the order the file names them in.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/tally/tally_declaration.hpp"

namespace scatterlab {

enum class DeclaredScore { exitance, transmittance, fluence, absorbed };

// One filter of a declared tally, as the file gives it: what it leaves out takes the filter's
// default (r and t start at 0; theta_o spans [0, pi/2]; order counts from 0), and
// check_declared_tallies refuses what is missing.
struct DeclaredFilter {
  Coordinate coordinate = Coordinate::r;
  std::optional<double> min, max;
  int bins = 0;
};

struct DeclaredTally {
  std::string name;  // letters, digits and _; unique in the file
  DeclaredScore score = DeclaredScore::exitance;
  std::vector<DeclaredFilter> filters;  // at most one of each coordinate
  // The medium's group index, where the geometry has no index of its own (the infinite
  // medium); elsewhere the index is the geometry's (eta over an outside of index 1, or each
  // layer's n).
  std::optional<double> group_index;

  const DeclaredFilter* filter(Coordinate coordinate) const;
};

// The filters' keys in filters = {...} ("x", "y", "r", "z", "rho", "theta_o", "t", "order",
// "layer"), in the order of their cells; and the coordinate of a key, or nullopt.
std::span<const std::string_view> declared_filter_keys();
std::optional<Coordinate> declared_filter(std::string_view key);

// What a geometry gives its declared tallies: which events it has, its length unit and how its
// walk's path becomes seconds.
struct DeclaredTallyFrame {
  std::string_view geometry;         // geometry.type, for refusals
  bool has_surface = true;           // exitance
  bool transmits = false;            // transmittance (a slab)
  bool has_volume_estimator = true;  // fluence
  bool has_index = true;             // refuses group_index (and needs none)
  std::string length_unit;           // the scene's: "mfp" has no seconds
  // Walk length units per scene length unit: sigma_t in a homogeneous medium (the walk runs in
  // mfp), 1 in a slab.
  double walk_per_unit = 1.0;
  // Seconds per unit of the walk's path at index 1 (the index is multiplied in: a homogeneous
  // geometry's own, or group_index; a slab's path carries each layer's n already).
  double seconds_per_walk_length = 0.0;
  double index = 1.0;  // the homogeneous medium's index, where it has one
  int layers = 0;      // a slab's, which the layer filter bins by
  // How the tallies' units name a length: "mfp" in a homogeneous medium (its tallies are
  // converted to the scene's unit after the run, transport/length_units.hpp), else the unit.
  std::string walk_length_label = "mfp";
};

// The frame of a homogeneous medium (the walk in mfp), of index `index` where the geometry has
// one (eta, over an outside of index 1), and of a slab in `length_unit`.
DeclaredTallyFrame homogeneous_frame(std::string_view geometry, const Medium& medium,
                                     std::optional<double> index);
DeclaredTallyFrame slab_frame(const std::string& length_unit, int layers);

// Throws InputError naming tally[i].<key> (from 1, as the reader names them) for a tally its
// geometry cannot score: an unknown pair, an axis out of range, a name taken twice, no seconds in
// a scene measured in mfp.
void check_declared_tallies(const std::vector<DeclaredTally>& tallies,
                            const DeclaredTallyFrame& frame);

// The chained tally declarations (tally/tally_declaration.hpp) of checked tallies, in the walk's
// units. Throws InputError naming tally[i].name when a name is one of `taken` (the geometry's
// own tallies).
std::vector<TallyDeclaration> declare_chained_tallies(const std::vector<DeclaredTally>& tallies,
                                                      const DeclaredTallyFrame& frame,
                                                      const std::vector<TallyDeclaration>& taken);

// What a spec's fingerprint adds for them: "" for none, so that a scene without [[tally]] keeps
// the fingerprint it always had.
std::string fingerprint_text(const std::vector<DeclaredTally>& tallies);

std::string to_string(DeclaredScore score);
// The score a [[tally]] names, or nullopt.
std::optional<DeclaredScore> declared_score(std::string_view name);

}  // namespace scatterlab
