#pragma once
// How absorption is scored along a walk.
//
//   analog            at each collision the photon is absorbed whole with probability
//                     1 - albedo (Vavassori §4.1): every photon ends in exactly one of exit,
//                     absorption or escape with weight 1, so energy balances photon by photon.
//   implicit_capture  MCML's scheme (Wang, Jacques & Zheng 1995; the MCML manual, Wang &
//                     Jacques 1992, "Photon absorption" and "Photon termination"): the
//                     photon carries a weight w, deposits w (1 - albedo) at each collision and
//                     goes on with w albedo; below roulette_threshold it survives with
//                     probability roulette_chance at w / roulette_chance, which keeps the
//                     expected weight and so the estimate unbiased. Energy balances in
//                     expectation, not photon by photon.

namespace scatterlab {

enum class Weighting { analog, implicit_capture };

// MCML's WEIGHT and CHANCE (the manual's "Photon termination").
inline constexpr double roulette_threshold = 1e-4;
inline constexpr double roulette_chance = 0.1;

}  // namespace scatterlab
