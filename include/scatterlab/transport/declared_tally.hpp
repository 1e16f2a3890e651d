#pragma once
// Tallies a scene declares ([[tally]] in a scene file, io/scene.hpp): a score at the filters a
// user names, beside the geometry's own tallies. The filters bin each event themselves (the
// Scorer's chain, tally/scorer.hpp), so any of them works on any score where the pair makes sense:
//
//   score          its event                                   filters
//   exitance       a photon leaves through the lit surface      x, y, r, theta_o, t, order;
//                  (an object: any of its surface)              phi on a plane; psi, azimuth
//                                                               on a sphere; triangle on a mesh
//   transmittance  a photon leaves a slab through its far side  x, y, r, theta_o, phi, t, order
//   fluence        a collision (the collision estimator)        x, y, r, z, rho, theta, phi, t,
//                                                               order
//   absorbed       a photon's weight is absorbed                the fluence's, and layer
//   collisions     a collision, counted (not 1 mfp)             the fluence's
//   path_length    as exitance, its weight times the path       the exitance's (not a slab,
//                  travelled since it entered                   whose walk keeps n l)
//
// x and y are the event's position (of an exit point on the surface, about the entry point; the
// beam arrives in the x-z plane), r the distance from the beam axis, z the depth, rho the
// distance from the source (the origin: a point source's fluence on shells), all in the scene's
// length unit. theta and phi are the direction of travel, theta from +z over [0, pi] and phi
// about z from +x over [0, 2 pi] (at an exit through a plane, the direction it leaves along:
// refraction keeps its azimuth); theta_o the exit angle from the outward normal, outside, over
// [0, pi/2]. theta and theta_o are per steradian, phi alone per radian, and phi with either of
// them per steradian of the cell. psi is an exit point's angle from a sphere's lit pole
// (0, 0, -R), over [0, pi], and azimuth its azimuth about z from +x; triangle a mesh's triangle
// (triangle = true: a bin per triangle): all per unit area of the surface. t is the time of flight
// in seconds since the light entered the medium: the path travelled times the group index over c
// (a slab's layers each at their own index n); order the number of scatterings, the last bin
// holding its order and more; layer a slab's layer, top down (layer = true: a bin per layer). A
// tally against t is the response to a unit impulse, per joule incident; one without t is per
// watt, as the geometry's own tallies are. Its cells are row-major in the order of the filter
// table (declared_filter_schema), whatever the order the file names them in.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/core/medium.hpp"
#include "scatterlab/tally/axis.hpp"
#include "scatterlab/tally/filter.hpp"
#include "scatterlab/tally/tally_declaration.hpp"

namespace scatterlab {

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
  Score score = Score::exitance;        // one of the six scores above
  std::vector<DeclaredFilter> filters;  // at most one of each coordinate
  // The medium's group index, where the geometry has no index of its own (the infinite
  // medium); elsewhere the index is the geometry's (eta over an outside of index 1, or each
  // layer's n).
  std::optional<double> group_index;

  const DeclaredFilter* filter(Coordinate coordinate) const;
};

// How a filter's axis is given: a length (max and bins, min 0 by default), a signed length (min
// too), a time in seconds (as a length), an angle over its whole range or a count (bins alone),
// or a bin for each layer or triangle (a switch: layer = true).
enum class FilterAxis { length, signed_length, seconds, angle, count, each };

// A filter as a scene writes it, for the reader and the schema (io/scene_schema.cpp writes its
// keys from these: min, max and bins of a length or a time, bins of an angle or a count, a
// boolean for each).
struct DeclaredFilterKey {
  std::string_view key;  // in filters = {...}: "x", "r", ..., "layer"
  FilterAxis axis;
  double range;                 // an angle's: [0, range]
  std::string_view geometries;  // the geometry.type values that take it, space-separated
  std::string_view meaning;     // of its bins
};

// Every filter, in the order of their cells; and the coordinate of a key, or nullopt.
std::vector<DeclaredFilterKey> declared_filter_schema();
std::optional<Coordinate> declared_filter(std::string_view key);

// What a geometry gives its declared tallies: which events it has, its length unit and how its
// walk's path becomes seconds.
// The surface light leaves a geometry through, which the filters of exits need.
enum class ExitSurface { none, plane, sphere, mesh };

struct DeclaredTallyFrame {
  std::string_view geometry;  // geometry.type, for refusals
  // None in the infinite medium (no exitance); a plane: the half-space, a slab's two sides.
  ExitSurface surface = ExitSurface::plane;
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
  double radius = 0.0;  // a sphere's, in the walk's length unit (psi and azimuth measure by it)
  std::vector<double> triangle_areas;  // a mesh's, in the walk's length unit squared
};

// The frame of a homogeneous medium (the walk in mfp), of index `index` where the geometry has
// one (eta, over an outside of index 1; its surface by geometry: "half_space", "sphere" or
// "mesh"), and of a slab in `length_unit`. A sphere's radius and a mesh's areas are the caller's.
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

// The score a [[tally]] names, or nullopt for a name that is not one of the six above.
std::optional<Score> declared_score(std::string_view name);

}  // namespace scatterlab
