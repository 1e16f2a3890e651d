#pragma once
// The infinite homogeneous medium (Vavassori §4.1): no surface, so the random walk holds no
// boundary code at all; photons end by absorption or, with a finite escape radius, by escape.

namespace scatterlab {

struct InfiniteMedium {
  static constexpr bool has_surface = false;
  static constexpr bool layered = false;
};

}  // namespace scatterlab
