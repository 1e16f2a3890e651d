#pragma once
// The random walk of random_walk.hpp, several photons at once in the lanes
// of the CPU's vector registers (2 with SSE4, 4 with AVX2, 8 with AVX-512; Google Highway picks
// the widest the machine has when the program runs, so one binary serves every x86-64). Eight
// photons are in flight whatever the width, a vector of them at a time, so that the order of
// their scores, and the run's bits, do not depend on it.
//
// Each lane follows one photon through the same events as RandomWalk: a free path, the surface,
// the collision scored, analog absorption, a new direction. What is done once for all lanes: the
// Philox4x32-10 call (the same words, to the bit, as PhotonRandom's: each photon's stream is still
// a pure function of (seed, photon index)), the log of the free path, the move, the phase
// function's cos theta and azimuth and the turn of the direction; which lanes make a plain event
// (the flight stays inside the surface and the escape radius, and the photon scatters), and,
// where the fluence phi(r, z) is the one volume score, each lane's cell. What stays one lane at a
// time: the plain event's adds into the tally buffer; and for the rest, launching a photon, the
// surface, scoring (Scorer, scattered into the tally buffer) and ending it.
// A lane whose photon ends takes the next photon of the range at once, so the lanes stay full until
// the range runs out.
//
// Same law, other bits than RandomWalk: the vector log is Highway's (within a few units in the
// last place of the library's), the turn may fuse a multiply and an add, the fluence cell's
// radius is rounded once (a fused x^2 + y^2), and the lanes' scores reach the buffer in another
// order. The paths are the same photon by photon until a rounding
// difference moves a collision across a bin edge; tests/unit/test_lane_walk.cpp holds the two
// walks to each other on the same photons. A range's scores depend on the range alone, so a run
// is still bitwise the same for any thread and rank count, and on any machine with fused
// multiply-adds (AVX2 and AVX-512 give the same bits; SSE4's unfused arithmetic rounds otherwise).
//
// For the infinite medium, the half-space, the sphere (with a beam, a point source or, on the
// sphere, its directional light) and a convex object another module traces (a triangle mesh with
// its own lights: object_boundary.hpp) under analog absorption and the collision estimator (or
// none), and for MCML's layered slab, analog or with implicit capture: the engine's choice there
// (kernel.hpp). The surface is the geometry's own code (half_space.hpp, sphere.hpp, slab.hpp,
// mesh/mesh_boundary.hpp), one lane at a time, on the lane's photon stream; an object's plain
// events are read off its grid of clearances for all lanes at once. In the slab each
// lane also carries its layer (whose Henyey-Greenstein g the vector turn reads per lane) and,
// under implicit capture, its weight. The track-length estimator keeps RandomWalk.

#include <cstdint>
#include <type_traits>
#include <variant>
#include <vector>

#include "scatterlab/tally/scorer.hpp"
#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/object_boundary.hpp"
#include "scatterlab/transport/random_walk.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/source.hpp"
#include "scatterlab/transport/sphere.hpp"
#include "scatterlab/transport/weighting.hpp"

namespace scatterlab {

// The geometries the lanes run, the one list of them (the engine runs a geometry on the lanes
// when it is one of these, kernel.hpp): the infinite medium, the half-space and the sphere under
// index-matched (eta = 1, no Fresnel arithmetic) or mismatched boundaries, the layered slab
// (slab.hpp), whose layers hold their own media, and a convex object with its light
// (object_boundary.hpp).
using LaneGeometry = std::variant<InfiniteMedium, HalfSpace<false>, HalfSpace<true>,
                                  Sphere<false>, Sphere<true>, Slab, ObjectBoundary>;

template <class Geometry, class = LaneGeometry>
inline constexpr bool is_lane_geometry = false;
template <class Geometry, class... Listed>
inline constexpr bool is_lane_geometry<Geometry, std::variant<Listed...>> =
    (std::is_same_v<Geometry, Listed> || ...);

class LaneWalk {
 public:
  // A homogeneous geometry (not the slab or an object, which have their own constructors below).
  // g = 0 samples isotropically (random_walk.hpp's IsotropicPhase), else Henyey-Greenstein g.
  // `estimator` none or collision, `source` a beam, a point or, on a sphere, the sphere light
  // (std::invalid_argument otherwise).
  LaneWalk(const LaneGeometry& geometry, const Scorer& scorer, const Source& source, double albedo,
           double g, Estimator estimator, double escape_radius, std::uint64_t seed);

  // The layered slab, scored at absorption and exit (no volume estimator), analog or with
  // implicit capture.
  LaneWalk(const Slab& slab, Weighting weighting, const Scorer& scorer, const Source& source,
           double escape_radius, std::uint64_t seed);

  // A convex object, lit by its own light (`object.launch`); `estimator` none or collision.
  LaneWalk(const ObjectBoundary& object, const Scorer& scorer, double albedo, double g,
           Estimator estimator, double escape_radius, std::uint64_t seed);

  std::vector<double> make_scratch() const { return {}; }

  // Transports photons [first, last) into `buffer`; returns the number of scattering events.
  std::uint64_t run(std::uint64_t first, std::uint64_t last, double* buffer,
                    std::vector<double>& scratch) const;

  // Doubles per vector in the instruction set chosen on this machine (the photons in flight,
  // eight, are that many vectors).
  static int lanes();

  // What the vector code reads (lane_walk.cpp).
  struct Setup {
    LaneGeometry geometry;
    const Scorer* scorer;
    Source source;  // unused for an object, whose light launches
    double albedo, g, escape_radius2;  // a slab's layers hold their own albedo and g
    bool scores_collisions;
    std::uint64_t seed;
    Weighting weighting = Weighting::analog;
  };

 private:
  Setup setup_;
};

}  // namespace scatterlab
