// The lane walk (lane_walk.hpp), compiled once per instruction set by Highway's foreach_target
// (this file includes itself through HWY_TARGET_INCLUDE) and dispatched at run time.
#include "scatterlab/transport/lane_walk.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "scatterlab/transport/half_space.hpp"
#include "scatterlab/transport/infinite_medium.hpp"
#include "scatterlab/transport/slab.hpp"
#include "scatterlab/transport/sphere.hpp"

// Highway's order: foreach_target, then highway.h, then its -inl.h headers.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/transport/lane_walk.cpp"
#include <hwy/foreach_target.h>
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace scatterlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using DU = hn::RebindToUnsigned<D>;  // 64-bit lanes holding one 32-bit Philox word each
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using VU = hn::Vec<DU>;

// Lanes of the widest vector any target compiled here has.
constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);

// Photons in flight at once, whatever the vector width: the vector steps go over them a vector
// at a time (one AVX-512 vector, two AVX2 ones), and the lanes' scores reach the buffer in one
// order. So a run's tallies are the same bits on every machine whose vectors fuse multiplies and
// adds (AVX2 and AVX-512 alike); SSE4's unfused arithmetic rounds otherwise. A power of two, as
// every vector width is, so that a whole number of vectors fills it.
constexpr std::size_t kLanes = kMaxLanes > 8 ? kMaxLanes : 8;

// A lane's flag stored as a vector mask (all bits set, or none).
HWY_INLINE bool flagged(double mask) {
  return std::bit_cast<std::uint64_t>(mask) != 0;
}

// Philox4x32-10 (Salmon et al. 2011; Random123's philox.h, whose multipliers and key increments
// these are) on the counters (photon low, photon high, call, 0) of every lane under one key: the
// same four words PhotonRandom::next4 gives, since each round is integer arithmetic. A round:
//   (hi0, lo0) = M0 c0, (hi1, lo1) = M1 c2 (32 x 32 -> 64 bits, the even-lane multiply),
//   c = (hi1 ^ c1 ^ k0, lo1, hi0 ^ c3 ^ k1, lo0), and the key grows by (W0, W1) between rounds.
struct PhiloxKeys {
  std::array<std::uint32_t, 10> k0, k1;  // the key of each round
};

PhiloxKeys philox_keys(std::uint64_t seed) {
  PhiloxKeys keys;
  auto k0 = static_cast<std::uint32_t>(seed), k1 = static_cast<std::uint32_t>(seed >> 32);
  for (std::size_t r = 0; r < 10; ++r) {
    keys.k0[r] = k0;
    keys.k1[r] = k1;
    k0 += PHILOX_W32_0;
    k1 += PHILOX_W32_1;
  }
  return keys;
}

// a b of lanes holding 32-bit values, in 64 bits: the even-lane multiply, or on a one-lane target
// (no 32-bit lanes to pair) the plain one.
HWY_INLINE VU multiply_32x32(VU a, VU b) {
#if HWY_TARGET == HWY_SCALAR
  const DU du;
  return hn::Set(du, hn::GetLane(a) * hn::GetLane(b));
#else
  const hn::Repartition<std::uint32_t, DU> d32;
  return hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, b));
#endif
}

// The four uniforms (k + 1/2) / 2^32 of each lane, as PhotonRandom::open_unit makes them.
HWY_INLINE void philox_uniforms(const PhiloxKeys& keys, VU photon, VU c2, V& u0, V& u1, V& u2,
                                V& u3) {
  const DU du;
  const D d;
  const VU low = hn::Set(du, 0xffffffffULL);
  VU c0 = hn::And(photon, low), c1 = hn::ShiftRight<32>(photon);
  const VU m0 = hn::Set(du, PHILOX_M4x32_0), m1 = hn::Set(du, PHILOX_M4x32_1);
  VU c3 = hn::Zero(du);
  for (std::size_t r = 0; r < 10; ++r) {
    const VU p0 = multiply_32x32(m0, c0);
    const VU p1 = multiply_32x32(m1, c2);
    const VU next0 = hn::Xor(hn::Xor(hn::ShiftRight<32>(p1), c1), hn::Set(du, keys.k0[r]));
    const VU next2 = hn::Xor(hn::Xor(hn::ShiftRight<32>(p0), c3), hn::Set(du, keys.k1[r]));
    c1 = hn::And(p1, low);
    c3 = hn::And(p0, low);
    c0 = next0;
    c2 = next2;
  }
  const DI di;
  const V half = hn::Set(d, 0.5), scale = hn::Set(d, 0x1p-32);
  const auto unit = [&](VU word) {
    return hn::Mul(hn::Add(hn::ConvertTo(d, hn::BitCast(di, word)), half), scale);
  };
  u0 = unit(c0);
  u1 = unit(c1);
  u2 = unit(c2);
  u3 = unit(c3);
}

// (cos 2 pi u, sin 2 pi u) in every lane: core/azimuth.hpp's series about the nearest quarter
// turn, the turn applied by masks instead of its sign table.
HWY_INLINE void azimuth(V u, V& cos_phi, V& sin_phi) {
  const D d;
  const DI di;
  const V quarters = hn::Mul(hn::Set(d, 4.0), u);
  const V q = hn::Round(quarters);
  const V x = hn::Mul(hn::Sub(quarters, q), hn::Set(d, 0.5 * std::numbers::pi));
  const V x2 = hn::Neg(hn::Mul(x, x));
  V s = hn::Set(d, azimuth_sin_series[0]);
  for (std::size_t i = 1; i < azimuth_sin_series.size(); ++i) {
    s = hn::MulAdd(s, x2, hn::Set(d, azimuth_sin_series[i]));
  }
  s = hn::Mul(s, x);
  V c = hn::Set(d, azimuth_cos_series[0]);
  for (std::size_t i = 1; i < azimuth_cos_series.size(); ++i) {
    c = hn::MulAdd(c, x2, hn::Set(d, azimuth_cos_series[i]));
  }
  // Quarter turns t = q mod 4: (c, s) -> (-s, c) per turn.
  const auto turn = hn::And(hn::ConvertTo(di, q), hn::Set(di, 3));
  const auto odd = hn::RebindMask(d, hn::Eq(hn::And(turn, hn::Set(di, 1)), hn::Set(di, 1)));
  const auto cos_negative =
      hn::RebindMask(d, hn::Or(hn::Eq(turn, hn::Set(di, 1)), hn::Eq(turn, hn::Set(di, 2))));
  const auto sin_negative = hn::RebindMask(d, hn::Gt(turn, hn::Set(di, 1)));
  const V cos_abs = hn::IfThenElse(odd, s, c), sin_abs = hn::IfThenElse(odd, c, s);
  cos_phi = hn::IfThenElse(cos_negative, hn::Neg(cos_abs), cos_abs);
  sin_phi = hn::IfThenElse(sin_negative, hn::Neg(sin_abs), sin_abs);
}

// cos theta of Henyey-Greenstein in every lane, each lane's g its own (the slab's layers differ):
// core/phase_function.hpp's cancellation-free inversion,
//   mu = s + 2 a x (1 - x) ((1 - a)(3 + a) + 4 a x) / ((1 - a) + 2 a x)^2,
// with a = |g|, x = xi, or 1 - xi and mu negated where g < 0.
HWY_INLINE V henyey_greenstein_cos(V g, V xi) {
  const D d;
  const V one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
  const V a = hn::Abs(g);
  const auto negative = hn::Lt(g, hn::Zero(d));
  const V x = hn::IfThenElse(negative, hn::Sub(one, xi), xi);
  const V s = hn::Sub(hn::Add(x, x), one);
  const V one_minus_a = hn::Sub(one, a), two_a = hn::Mul(two, a);
  const V den = hn::MulAdd(two_a, x, one_minus_a);
  const V num = hn::Mul(hn::Mul(hn::Mul(two_a, x), hn::Sub(one, x)),
                        hn::MulAdd(hn::Mul(hn::Set(d, 4.0), a), x,
                                   hn::Mul(one_minus_a, hn::Add(hn::Set(d, 3.0), a))));
  const V mu = hn::Min(hn::Max(hn::Add(s, hn::Div(num, hn::Mul(den, den))), hn::Neg(one)), one);
  return hn::IfThenElse(negative, hn::Neg(mu), mu);
}

// The direction at cos theta from (wx, wy, wz) and azimuth phi about it, in place: core/frame.hpp's
// Frame (Duff et al. 2017) and its one Newton step back onto the unit sphere.
HWY_INLINE void turn_direction(V cos_theta, V cos_phi, V sin_phi, V& wx, V& wy, V& wz) {
  const D d;
  const V one = hn::Set(d, 1.0);
  const V sin_theta =
      hn::Sqrt(hn::Max(hn::Zero(d), hn::Mul(hn::Sub(one, cos_theta), hn::Add(one, cos_theta))));
  const V sign = hn::CopySign(one, wz);
  const V a = hn::Neg(hn::Div(one, hn::Add(sign, wz)));
  const V b = hn::Mul(hn::Mul(wx, wy), a);
  const V tx = hn::MulAdd(hn::Mul(sign, hn::Mul(wx, wx)), a, one), ty = hn::Mul(sign, b),
          tz = hn::Neg(hn::Mul(sign, wx));
  const V bx = b, by = hn::MulAdd(hn::Mul(wy, wy), a, sign), bz = hn::Neg(wy);
  const V along_t = hn::Mul(sin_theta, cos_phi), along_b = hn::Mul(sin_theta, sin_phi);
  const V nx = hn::MulAdd(along_t, tx, hn::MulAdd(along_b, bx, hn::Mul(cos_theta, wx)));
  const V ny = hn::MulAdd(along_t, ty, hn::MulAdd(along_b, by, hn::Mul(cos_theta, wy)));
  const V nz = hn::MulAdd(along_t, tz, hn::MulAdd(along_b, bz, hn::Mul(cos_theta, wz)));
  const V norm2 = hn::MulAdd(nx, nx, hn::MulAdd(ny, ny, hn::Mul(nz, nz)));
  const V pull = hn::Mul(hn::Set(d, 0.5), hn::Sub(hn::Set(d, 3.0), norm2));
  wx = hn::Mul(nx, pull);
  wy = hn::Mul(ny, pull);
  wz = hn::Mul(nz, pull);
}

// Where the flight ending at (x, y, z) certainly stays inside the geometry: the lanes whose
// surface test (the geometry's leaves(), one lane at a time) would find no crossing. The
// half-space's test is the same comparison on the same z; the sphere's keeps a margin of 1e-12
// of R^2, so that a sum rounded otherwise than Eigen's squaredNorm never passes a photon that
// crosses (those near the surface take the lane-by-lane path, which decides exactly).
HWY_INLINE auto stays_inside(const InfiniteMedium&, const LaneWalk::Setup&, V, V, V) {
  const D d;
  return hn::Eq(hn::Zero(d), hn::Zero(d));  // every lane: there is no surface
}
template <bool fresnel>
HWY_INLINE auto stays_inside(const HalfSpace<fresnel>&, const LaneWalk::Setup&, V, V, V z) {
  return hn::Not(hn::Lt(z, hn::Zero(D())));
}
template <bool fresnel>
HWY_INLINE auto stays_inside(const Sphere<fresnel>& sphere, const LaneWalk::Setup&, V x, V y, V z) {
  const D d;
  const V r2 = hn::MulAdd(x, x, hn::MulAdd(y, y, hn::Mul(z, z)));
  return hn::Lt(r2, hn::Set(d, sphere.radius() * sphere.radius() * (1.0 - 1e-12)));
}
// A convex object's (object_boundary.hpp): the end lies below every face of a polyhedron of few
// faces; or in the object's core, or in a cell wholly inside (InteriorClearance::at positive).
// The grid is read lane by lane, and only for the lanes out of the core: in a round object
// those are few and mostly beyond the surface, and a gather would read a cell for every lane,
// each a likely cache miss.
HWY_INLINE auto stays_inside(const ObjectBoundary& object, const LaneWalk::Setup&, V x, V y, V z) {
  const D d;
  const InteriorClearance& grid = object.interior();
  const V ox = hn::Sub(x, hn::Set(d, grid.core_centre.x()));
  const V oy = hn::Sub(y, hn::Set(d, grid.core_centre.y()));
  const V oz = hn::Sub(z, hn::Set(d, grid.core_centre.z()));
  if (grid.faces > 0) {
    auto below = hn::Eq(hn::Zero(d), hn::Zero(d));  // every lane
    for (int i = 0; i < grid.faces; ++i) {
      const V height = hn::MulAdd(
          ox, hn::Set(d, grid.face_x[i]),
          hn::MulAdd(oy, hn::Set(d, grid.face_y[i]), hn::Mul(oz, hn::Set(d, grid.face_z[i]))));
      below = hn::And(below, hn::Lt(height, hn::Set(d, grid.face_offset[i])));
    }
    return below;
  }
  const auto in_core = hn::Lt(hn::MulAdd(ox, ox, hn::MulAdd(oy, oy, hn::Mul(oz, oz))),
                              hn::Set(d, grid.core_radius2));
  if (hn::AllTrue(d, in_core)) return in_core;
  alignas(64) double px[kMaxLanes], py[kMaxLanes], pz[kMaxLanes];
  hn::Store(x, d, px);
  hn::Store(y, d, py);
  hn::Store(z, d, pz);
  std::uint8_t bits[(kMaxLanes + 7) / 8 + 8] = {};
  hn::StoreMaskBits(d, in_core, bits);
  for (std::size_t k = 0; k < hn::Lanes(d); ++k) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1U << (k % 8));
    if (!(bits[k / 8] & bit) && grid.at(Vec3(px[k], py[k], pz[k])) > 0.0) bits[k / 8] |= bit;
  }
  return hn::LoadMaskBits(d, bits);
}

// One photon per lane; the arrays are the lanes' state between vector steps.
struct Lanes {
  alignas(64) double x[kLanes], y[kLanes], z[kLanes];      // position
  alignas(64) double wx[kLanes], wy[kLanes], wz[kLanes];   // direction
  alignas(64) std::uint64_t photon[kLanes], call[kLanes];  // Philox counter words 0-1, 2
  alignas(64) double u1[kLanes], u2[kLanes], u3[kLanes];
  alignas(64) double next_x[kLanes], next_y[kLanes], next_z[kLanes];
  alignas(64) double flight[kLanes];  // mfp, or optical depth in the slab
  alignas(64) double g[kLanes];       // the slab: the Henyey-Greenstein g of the lane's layer
  double weight[kLanes];              // implicit capture
  int order[kLanes];
  int layer[kLanes];  // the slab
  bool busy[kLanes];
  alignas(64) std::int64_t cell[kLanes];  // the fluence cell of the flight's end, or -1
  // Masks (flagged()): the photon scatters now; its flight stays inside, and it scatters; its
  // flight stays inside.
  alignas(64) double scatters[kLanes], plain[kLanes], inside[kLanes];
};

// `isotropic`: g = 0 everywhere (never in the slab, whose g is per layer); `collisions`: the
// collision estimator; `implicit`: implicit capture (the slab alone).
template <class Geometry, bool isotropic, bool collisions, bool implicit>
std::uint64_t run_lanes(const Geometry& geometry, const LaneWalk::Setup& setup, std::uint64_t first,
                        std::uint64_t last, double* buffer) {
  static_assert(!(Geometry::layered && (isotropic || collisions)));
  const D d;
  const DU du;
  const std::size_t n = hn::Lanes(d);  // divides kLanes: both are powers of two, n <= kMaxLanes
  const Scorer& scorer = *setup.scorer;
  const PhiloxKeys keys = philox_keys(setup.seed);
  Lanes lane{};
  std::uint64_t next_photon = first, scatterings = 0;

  // Gives `k` the next photon that enters (a source may reflect some off before they do);
  // false when the range is done.
  const auto launch = [&](std::size_t k) {
    while (next_photon < last) {
      const std::uint64_t photon = next_photon++;
      PhotonRandom random(setup.seed, photon);
      Vec3 start = Vec3::Zero(), heading = Vec3::UnitZ();
      bool enters = false;
      if constexpr (std::is_same_v<Geometry, ObjectBoundary>) {
        enters = geometry.launch(random, start, heading);
      } else {
        enters = setup.source.launch(random, start, heading);
      }
      if (!enters) {
        scorer.reflection_at_entry(buffer);
        continue;
      }
      lane.x[k] = start.x(), lane.y[k] = start.y(), lane.z[k] = start.z();
      lane.wx[k] = heading.x(), lane.wy[k] = heading.y(), lane.wz[k] = heading.z();
      lane.photon[k] = photon;
      lane.call[k] = random.calls();
      lane.order[k] = 0;
      if constexpr (Geometry::layered) lane.layer[k] = geometry.layer_of(start, heading);
      if constexpr (implicit) lane.weight[k] = 1.0;
      return true;
    }
    // An idle lane keeps a unit direction, so that its (discarded) turns stay finite.
    lane.wx[k] = 0.0, lane.wy[k] = 0.0, lane.wz[k] = 1.0;
    return false;
  };
  std::size_t busy = 0;
  for (std::size_t k = 0; k < kLanes; ++k) busy += (lane.busy[k] = launch(k));
  // Where the one volume score is phi(r, z), its cells (only with the collision estimator).
  const std::optional<Scorer::FluenceCells> cells =
      collisions ? scorer.fluence_cells() : std::nullopt;
  const DI di;
  // Within the escape radius for certain: by the same margin as the sphere's surface.
  const bool escape_limited = std::isfinite(setup.escape_radius2);
  const double plain_escape_radius2 = setup.escape_radius2 * (1.0 - 1e-12);

  while (busy > 0) {
    // The event's four uniforms and the free path for every lane, a vector at a time, and
    // outside the slab (which spends a free path layer by layer) the move.
    for (std::size_t c = 0; c < kLanes; c += n) {
      V u0, u1, u2, u3;
      const VU call = hn::Load(du, lane.call + c);
      philox_uniforms(keys, hn::Load(du, lane.photon + c), call, u0, u1, u2, u3);
      hn::Store(hn::Add(call, hn::Set(du, 1)), du, lane.call + c);
      hn::Store(u1, d, lane.u1 + c);
      hn::Store(u2, d, lane.u2 + c);
      hn::Store(u3, d, lane.u3 + c);
      const V flight = hn::Neg(hn::Log(d, u0));
      hn::Store(flight, d, lane.flight + c);
      if constexpr (!Geometry::layered) {
        const V wx = hn::Load(d, lane.wx + c), wy = hn::Load(d, lane.wy + c),
                wz = hn::Load(d, lane.wz + c);
        const V next_x = hn::MulAdd(flight, wx, hn::Load(d, lane.x + c));
        const V next_y = hn::MulAdd(flight, wy, hn::Load(d, lane.y + c));
        const V next_z = hn::MulAdd(flight, wz, hn::Load(d, lane.z + c));
        hn::Store(next_x, d, lane.next_x + c);
        hn::Store(next_y, d, lane.next_y + c);
        hn::Store(next_z, d, lane.next_z + c);
        // The plain event, most of them: the flight stays inside, within the escape radius, and
        // the photon scatters. Such a lane needs only its move and its collision scored.
        const auto inside = stays_inside(geometry, setup, next_x, next_y, next_z);
        if constexpr (Geometry::has_surface)
          hn::Store(hn::VecFromMask(d, inside), d, lane.inside + c);
        auto plain = hn::And(hn::Lt(u1, hn::Set(d, setup.albedo)), inside);
        if (escape_limited) {
          const V r2 =
              hn::MulAdd(next_x, next_x, hn::MulAdd(next_y, next_y, hn::Mul(next_z, next_z)));
          plain = hn::And(plain, hn::Lt(r2, hn::Set(d, plain_escape_radius2)));
        }
        hn::Store(hn::VecFromMask(d, plain), d, lane.plain + c);
        if (cells) {
          // Scorer::collision's cell, for all lanes: (r, z) on the grid, or -1 off it.
          const V r = hn::Sqrt(hn::MulAdd(next_x, next_x, hn::Mul(next_y, next_y)));
          const V ur =
              hn::Mul(hn::Sub(r, hn::Set(d, cells->r.min)), hn::Set(d, cells->r.inverse_width));
          const V uz = hn::Mul(hn::Sub(next_z, hn::Set(d, cells->z.min)),
                               hn::Set(d, cells->z.inverse_width));
          const V zero = hn::Zero(d);
          const auto on_grid =
              hn::And(hn::And(hn::Ge(ur, zero), hn::Lt(ur, hn::Set(d, cells->r.end))),
                      hn::And(hn::Ge(uz, zero), hn::Lt(uz, hn::Set(d, cells->z.end))));
          const V cell = hn::MulAdd(hn::Trunc(ur), hn::Set(d, static_cast<double>(cells->z_bins)),
                                    hn::Trunc(uz));
          hn::Store(hn::ConvertTo(di, hn::IfThenElse(on_grid, cell, hn::Set(d, -1.0))), di,
                    lane.cell + c);
        }
      }
    }

    // Lane k collides at its position after its flight, and scatters: what both paths below do.
    const auto collide = [&](std::size_t k) {
      if constexpr (collisions) {
        scorer.collision(buffer, Vec3(lane.x[k], lane.y[k], lane.z[k]),
                         Vec3(lane.wx[k], lane.wy[k], lane.wz[k]), lane.order[k]);
      }
    };
    const auto scatter = [&](std::size_t k) {
      lane.scatters[k] = std::bit_cast<double>(~std::uint64_t{0});
      ++lane.order[k];
      ++scatterings;
    };

    // Each lane's surface, escape, collision and absorption, in lane order (the buffer's order of
    // adds), as RandomWalk::run has them.
    for (std::size_t k = 0; k < kLanes; ++k) {
      lane.scatters[k] = 0.0;
      if (!lane.busy[k]) continue;
      if constexpr (!Geometry::layered) {
        if (flagged(lane.plain[k])) {
          // What the general path below does with such a lane, without its tests.
          lane.x[k] = lane.next_x[k], lane.y[k] = lane.next_y[k], lane.z[k] = lane.next_z[k];
          if (!cells) {
            collide(k);
          } else if (lane.cell[k] >= 0) {
            scorer.collision_in_cell(buffer, static_cast<std::size_t>(lane.cell[k]), lane.order[k]);
          }
          scatter(k);
          continue;
        }
      }
      // Constant 1 under analog absorption, where the compiler folds it away.
      double weight = 1.0;
      if constexpr (implicit) weight = lane.weight[k];
      Vec3 next(lane.next_x[k], lane.next_y[k], lane.next_z[k]);  // the slab's: from its surface
      bool left = false;
      if constexpr (Geometry::has_surface) {
        // A flight the vector test found inside (then absorbed) meets no surface. (The slab,
        // which spends its free paths layer by layer, has no such test.)
        const bool inside = !Geometry::layered && flagged(lane.inside[k]);
        if (!inside) {
          // The geometry's own code on the lane's stream (a Fresnel choice draws from it).
          Vec3 position(lane.x[k], lane.y[k], lane.z[k]);
          Vec3 direction(lane.wx[k], lane.wy[k], lane.wz[k]);
          PhotonRandom random(setup.seed, lane.photon[k], static_cast<std::uint32_t>(lane.call[k]));
          SurfaceExit exit;
          if constexpr (Geometry::layered) {
            left =
                geometry.leaves(position, direction, lane.layer[k], lane.flight[k], random, exit);
            next = position;
          } else {
            left = geometry.leaves(position, direction, next, lane.flight[k], random, exit);
          }
          if (left) {
            scorer.exit(buffer, exit, lane.order[k], weight);
          } else {
            lane.wx[k] = direction.x(), lane.wy[k] = direction.y(), lane.wz[k] = direction.z();
            lane.call[k] = random.calls();
          }
        }
      }
      if (!left && next.squaredNorm() > setup.escape_radius2) {
        scorer.escape(buffer, weight);
      } else if (!left) {
        lane.x[k] = next.x(), lane.y[k] = next.y(), lane.z[k] = next.z();
        collide(k);
        double albedo = setup.albedo;
        int layer = 0;
        if constexpr (Geometry::layered) {
          layer = lane.layer[k];
          albedo = geometry.albedo(layer);
          lane.g[k] = geometry.g(layer);
        }
        bool scatters = lane.u1[k] < albedo;
        if constexpr (implicit) {
          // RandomWalk's drop and roulette (weighting.hpp), with u1 for the roulette.
          const double deposited = weight * (1.0 - albedo);
          scorer.absorption(buffer, next, lane.order[k], layer, deposited);
          weight -= deposited;
          scatters = true;
          if (weight < roulette_threshold) {
            scatters = weight > 0.0 && lane.u1[k] < roulette_chance;
            weight /= roulette_chance;
          }
          lane.weight[k] = weight;
        } else if (!scatters) {
          scorer.absorption(buffer, next, lane.order[k], layer);
        }
        if (scatters) {
          scatter(k);
          continue;
        }
      }
      if (!(lane.busy[k] = launch(k))) --busy;
    }

    // The scattered lanes' new directions; the others (new photons, idle lanes) keep theirs. (A
    // surface may have turned a direction since the move.)
    for (std::size_t c = 0; c < kLanes; c += n) {
      V nx = hn::Load(d, lane.wx + c), ny = hn::Load(d, lane.wy + c), nz = hn::Load(d, lane.wz + c),
        cos_phi, sin_phi;
      azimuth(hn::Load(d, lane.u3 + c), cos_phi, sin_phi);
      if constexpr (isotropic) {
        // Drawn afresh about +z (core/frame.hpp: isotropic scattering forgets the old direction).
        const V one = hn::Set(d, 1.0), u2 = hn::Load(d, lane.u2 + c);
        nz = hn::Sub(hn::Add(u2, u2), one);
        const V s = hn::Sqrt(hn::Max(hn::Zero(d), hn::Mul(hn::Sub(one, nz), hn::Add(one, nz))));
        nx = hn::Mul(s, cos_phi);
        ny = hn::Mul(s, sin_phi);
      } else {
        const V g = Geometry::layered ? hn::Load(d, lane.g + c) : hn::Set(d, setup.g);
        turn_direction(henyey_greenstein_cos(g, hn::Load(d, lane.u2 + c)), cos_phi, sin_phi, nx, ny,
                       nz);
      }
      const auto scatters = hn::MaskFromVec(hn::Load(d, lane.scatters + c));
      hn::Store(hn::IfThenElse(scatters, nx, hn::Load(d, lane.wx + c)), d, lane.wx + c);
      hn::Store(hn::IfThenElse(scatters, ny, hn::Load(d, lane.wy + c)), d, lane.wy + c);
      hn::Store(hn::IfThenElse(scatters, nz, hn::Load(d, lane.wz + c)), d, lane.wz + c);
    }
  }
  return scatterings;
}

template <class Geometry>
std::uint64_t run_on(const Geometry& geometry, const LaneWalk::Setup& setup, std::uint64_t first,
                     std::uint64_t last, double* buffer) {
  const bool isotropic = setup.g == 0.0;
  if (setup.scores_collisions) {
    return isotropic
               ? run_lanes<Geometry, true, true, false>(geometry, setup, first, last, buffer)
               : run_lanes<Geometry, false, true, false>(geometry, setup, first, last, buffer);
  }
  return isotropic ? run_lanes<Geometry, true, false, false>(geometry, setup, first, last, buffer)
                   : run_lanes<Geometry, false, false, false>(geometry, setup, first, last, buffer);
}

std::uint64_t RunLanes(const LaneWalk::Setup& setup, std::uint64_t first, std::uint64_t last,
                       double* buffer) {
  return std::visit(
      [&](const auto& geometry) {
        if constexpr (std::is_same_v<std::decay_t<decltype(geometry)>, Slab>) {
          return setup.weighting == Weighting::implicit_capture
                     ? run_lanes<Slab, false, false, true>(geometry, setup, first, last, buffer)
                     : run_lanes<Slab, false, false, false>(geometry, setup, first, last, buffer);
        } else {
          return run_on(geometry, setup, first, last, buffer);
        }
      },
      setup.geometry);
}

int LaneCount() {
  return static_cast<int>(hn::Lanes(D()));
}

}  // namespace HWY_NAMESPACE
}  // namespace scatterlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace scatterlab {

HWY_EXPORT(RunLanes);
HWY_EXPORT(LaneCount);

namespace {

void refuse_track_length(Estimator estimator) {
  if (estimator == Estimator::track_length) {
    throw std::invalid_argument("LaneWalk: the track-length estimator runs on RandomWalk");
  }
}

void refuse_sphere_light_off_the_sphere(const LaneGeometry& geometry, const Source& source) {
  if (source.kind == Source::Kind::sphere_light &&
      !std::holds_alternative<Sphere<false>>(geometry) &&
      !std::holds_alternative<Sphere<true>>(geometry)) {
    throw std::invalid_argument("LaneWalk: a sphere light needs the sphere's geometry");
  }
}

}  // namespace

LaneWalk::LaneWalk(const LaneGeometry& geometry, const Scorer& scorer, const Source& source,
                   double albedo, double g, Estimator estimator, double escape_radius,
                   std::uint64_t seed)
    : setup_{geometry, &scorer, source, albedo, g, escape_radius * escape_radius,
             estimator == Estimator::collision, seed, Weighting::analog} {
  refuse_track_length(estimator);
  if (std::holds_alternative<Slab>(geometry)) {
    throw std::invalid_argument(
        "LaneWalk: a layered slab takes the constructor with its weighting");
  }
  if (std::holds_alternative<ObjectBoundary>(geometry)) {
    throw std::invalid_argument(
        "LaneWalk: an object takes the constructor without a source (its light launches)");
  }
  refuse_sphere_light_off_the_sphere(geometry, source);
}

LaneWalk::LaneWalk(const Slab& slab, Weighting weighting, const Scorer& scorer,
                   const Source& source, double escape_radius, std::uint64_t seed)
    : setup_{slab,
             &scorer,
             source,
             0.0,  // each layer's albedo and g are the slab's
             0.0,
             escape_radius * escape_radius,
             false,
             seed,
             weighting} {
  refuse_sphere_light_off_the_sphere(setup_.geometry, source);
}

LaneWalk::LaneWalk(const ObjectBoundary& object, const Scorer& scorer, double albedo, double g,
                   Estimator estimator, double escape_radius, std::uint64_t seed)
    : setup_{object,
             &scorer,
             Source{},  // unused: the object's light launches
             albedo,
             g,
             escape_radius * escape_radius,
             estimator == Estimator::collision,
             seed,
             Weighting::analog} {
  refuse_track_length(estimator);
}

std::uint64_t LaneWalk::run(std::uint64_t first, std::uint64_t last, double* buffer,
                            std::vector<double>& /*scratch*/) const {
  return HWY_DYNAMIC_DISPATCH(RunLanes)(setup_, first, last, buffer);
}

int LaneWalk::lanes() {
  return HWY_DYNAMIC_DISPATCH(LaneCount)();
}

}  // namespace scatterlab
#endif
