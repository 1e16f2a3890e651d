// The bin averages of lobe_bin_average.hpp, compiled once per instruction set by Highway's
// foreach_target (this file includes itself through HWY_TARGET_INCLUDE) and dispatched at run
// time.
#include "lobe_bin_average.hpp"

#include <cmath>
#include <limits>

// Highway's order: foreach_target, then highway.h, then its -inl.h headers.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "fit/lobe_bin_average.cpp"
#include <hwy/foreach_target.h>
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace scatterlab::fit {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;

// R = (e^x - 1) / gamma and dR/dgamma = (x e^x - (e^x - 1)) / gamma^2 at x = gamma s, each by
// its series where the closed form cancels: R as lobe_model.hpp's exp_ramp, and
// dR/dgamma = s^2 sum_{n >= 2} (n - 1) x^{n-2} / n! = s^2 (1/2 + x/3 + x^2/8 + x^3/30 + ...),
// whose next term, x^4/144, is below 1e-14 for |x| < 1e-3. Highway's Expm1 is valid up to
// x = 706; above it R is +infinity, as libm's expm1 makes it from about 709.8 (a trial step
// that reaches it is rejected).
struct Ramp {
  explicit Ramp(double g)
      : small(!(std::abs(g) > 1e-6)),
        gamma(hn::Set(D(), g)),
        inverse(hn::Set(D(), 1.0 / g)),
        inverse_squared(hn::Set(D(), 1.0 / (g * g))) {}
  bool small;  // |gamma| <= 1e-6: R by its series (the closed form's division cancels)
  V gamma, inverse, inverse_squared;

  // e^x - 1 and R at s.
  HWY_INLINE void operator()(V s, V& grown, V& ramp) const {
    const D d;
    const V x = hn::Mul(gamma, s);
    grown = hn::IfThenElse(hn::Gt(x, hn::Set(d, 706.0)),
                           hn::Set(d, std::numeric_limits<double>::infinity()), hn::Expm1(d, x));
    ramp = small ? hn::Mul(s, hn::MulAdd(x, hn::MulAdd(x, hn::Set(d, 1.0 / 6.0), hn::Set(d, 0.5)),
                                         hn::Set(d, 1.0)))
                 : hn::Mul(grown, inverse);
  }
  // dR/dgamma at s, given e^x - 1 there.
  HWY_INLINE V derivative(V s, V grown) const {
    const D d;
    const V x = hn::Mul(gamma, s);
    const V series =
        hn::Mul(hn::Mul(s, s),
                hn::MulAdd(x,
                           hn::MulAdd(x, hn::MulAdd(x, hn::Set(d, 1.0 / 30.0), hn::Set(d, 0.125)),
                                      hn::Set(d, 1.0 / 3.0)),
                           hn::Set(d, 0.5)));
    // x e^x - (e^x - 1) = x (e^x - 1) + x - (e^x - 1)
    const V closed = hn::Mul(hn::Sub(hn::MulAdd(x, grown, x), grown), inverse_squared);
    return hn::IfThenElse(hn::Lt(hn::Abs(x), hn::Set(d, 1e-3)), series, closed);
  }
};

// Pass 1 keeps what pass 2 needs of each node, one vector each per slot.
enum Term { kLog, kU, kV, kRho, kS, kRamp, kRampGamma, kGrowth, kTerms };

template <bool kJacobian>
void average_over_bins(const LobeTerms& lobe, const BinNodes& nodes, BinAverages& out) {
  const D d;
  const std::size_t lanes = hn::Lanes(d), stride = nodes.padded_bins;
  HWY_ASSERT(stride % lanes == 0);
  thread_local std::vector<double> scratch;
  scratch.resize(kTerms * nodes.slots * lanes);
  const auto term = [&](std::size_t q, Term t) {
    return scratch.data() + (q * kTerms + t) * lanes;
  };

  // p, and t1 and t2, whose projections on a node are u and v.
  const V ax = hn::Set(d, lobe.axis[0]), ay = hn::Set(d, lobe.axis[1]),
          az = hn::Set(d, lobe.axis[2]);
  const V ux = hn::Set(d, lobe.t1[0]), uy = hn::Set(d, lobe.t1[1]), uz = hn::Set(d, lobe.t1[2]);
  const V vx = hn::Set(d, lobe.t2[0]), vy = hn::Set(d, lobe.t2[1]), vz = hn::Set(d, lobe.t2[2]);
  const V a = hn::Set(d, lobe.a), b = hn::Set(d, lobe.b);
  const V along = hn::Set(d, lobe.along_scale), across = hn::Set(d, lobe.across_scale);
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5), zero = hn::Zero(d);
  const Ramp ramp(lobe.gamma);

  for (std::size_t bin = 0; bin < stride; bin += lanes) {
    // Pass 1: l at every node, and the bin's largest.
    V largest = hn::Set(d, -std::numeric_limits<double>::infinity());
    for (std::size_t q = 0; q < nodes.slots; ++q) {
      const std::size_t at = q * stride + bin;
      const V wx = hn::LoadU(d, nodes.x.data() + at), wy = hn::LoadU(d, nodes.y.data() + at),
              wz = hn::LoadU(d, nodes.z.data() + at);
      const V u = hn::MulAdd(uz, wz, hn::MulAdd(uy, wy, hn::Mul(ux, wx)));
      const V v = hn::MulAdd(vz, wz, hn::MulAdd(vy, wy, hn::Mul(vx, wx)));
      const V rho = hn::Sub(one, hn::MulAdd(az, wz, hn::MulAdd(ay, wy, hn::Mul(ax, wx))));
      const V s_squared =
          hn::MulAdd(along, hn::Mul(u, u),
                     hn::MulAdd(across, hn::Mul(v, v), hn::Mul(half, hn::Mul(rho, rho))));
      const V s = hn::Sqrt(hn::Max(s_squared, zero));
      V grown, ramp_value;
      ramp(s, grown, ramp_value);
      const V log_value = hn::MulAdd(b, ramp_value, a);
      largest = hn::Max(largest, log_value);
      hn::StoreU(log_value, d, term(q, kLog));
      if constexpr (kJacobian) {
        hn::StoreU(u, d, term(q, kU));
        hn::StoreU(v, d, term(q, kV));
        hn::StoreU(rho, d, term(q, kRho));
        hn::StoreU(s, d, term(q, kS));
        hn::StoreU(ramp_value, d, term(q, kRamp));
        hn::StoreU(ramp.derivative(s, grown), d, term(q, kRampGamma));
        hn::StoreU(hn::Add(grown, one), d, term(q, kGrowth));
      }
    }
    // Pass 2: the weights w'_q = w_q e^{l_q - largest} and the gradient's sums.
    V sum = zero, sum_ramp = zero, sum_ramp_gamma = zero, sum_along = zero, sum_across = zero;
    V d_t1x = zero, d_t1y = zero, d_t1z = zero, d_t2x = zero, d_t2y = zero, d_t2z = zero,
      d_px = zero, d_py = zero, d_pz = zero;
    for (std::size_t q = 0; q < nodes.slots; ++q) {
      const std::size_t at = q * stride + bin;
      const V weight = hn::Mul(hn::LoadU(d, nodes.weight.data() + at),
                               hn::Exp(d, hn::Sub(hn::LoadU(d, term(q, kLog)), largest)));
      sum = hn::Add(sum, weight);
      if constexpr (kJacobian) {
        const V u = hn::LoadU(d, term(q, kU)), v = hn::LoadU(d, term(q, kV));
        const V rho = hn::LoadU(d, term(q, kRho)), s = hn::LoadU(d, term(q, kS));
        // A node whose weight underflowed to 0 adds nothing, though its R or e^{gamma s} may be
        // infinite (0 inf would be NaN): there l = a + b R falls to -infinity faster than the
        // factors grow, so each product's limit is 0.
        const auto live = hn::Gt(weight, zero);
        // g = w' b e^{gamma s} / (2 s), 0 at s = 0 (the subgradient of lobe_model.hpp)
        const V g = hn::IfThenElseZero(
            hn::And(live, hn::Gt(s, zero)),
            hn::Div(hn::Mul(hn::Mul(weight, b), hn::LoadU(d, term(q, kGrowth))), hn::Add(s, s)));
        sum_ramp = hn::Add(sum_ramp,
                           hn::IfThenElseZero(live, hn::Mul(weight, hn::LoadU(d, term(q, kRamp)))));
        sum_ramp_gamma =
            hn::Add(sum_ramp_gamma,
                    hn::IfThenElseZero(live, hn::Mul(weight, hn::LoadU(d, term(q, kRampGamma)))));
        const V gu = hn::Mul(g, u), gv = hn::Mul(g, v), grho = hn::Mul(g, rho);
        sum_along = hn::MulAdd(gu, u, sum_along);
        sum_across = hn::MulAdd(gv, v, sum_across);
        const V wx = hn::LoadU(d, nodes.x.data() + at), wy = hn::LoadU(d, nodes.y.data() + at),
                wz = hn::LoadU(d, nodes.z.data() + at);
        d_t1x = hn::MulAdd(gu, wx, d_t1x);
        d_t1y = hn::MulAdd(gu, wy, d_t1y);
        d_t1z = hn::MulAdd(gu, wz, d_t1z);
        d_t2x = hn::MulAdd(gv, wx, d_t2x);
        d_t2y = hn::MulAdd(gv, wy, d_t2y);
        d_t2z = hn::MulAdd(gv, wz, d_t2z);
        d_px = hn::MulAdd(grho, wx, d_px);
        d_py = hn::MulAdd(grho, wy, d_py);
        d_pz = hn::MulAdd(grho, wz, d_pz);
      }
    }
    // e^{largest}; above 706 (Highway's range) +infinity, as libm's exp makes it from 709.8
    hn::StoreU(
        hn::IfThenElse(hn::Gt(largest, hn::Set(d, 706.0)),
                       hn::Set(d, std::numeric_limits<double>::infinity()), hn::Exp(d, largest)),
        d, out.scale.data() + bin);
    hn::StoreU(sum, d, out.sum.data() + bin);
    if constexpr (kJacobian) {
      // The constant factors, once per bin: b, 2A, 2B and -1.
      const V twice_along = hn::Add(along, along), twice_across = hn::Add(across, across);
      hn::StoreU(sum_ramp, d, out.ramp.data() + bin);
      hn::StoreU(hn::Mul(b, sum_ramp_gamma), d, out.ramp_gamma.data() + bin);
      hn::StoreU(sum_along, d, out.along.data() + bin);
      hn::StoreU(sum_across, d, out.across.data() + bin);
      hn::StoreU(hn::Mul(twice_along, d_t1x), d, out.d_t1[0].data() + bin);
      hn::StoreU(hn::Mul(twice_along, d_t1y), d, out.d_t1[1].data() + bin);
      hn::StoreU(hn::Mul(twice_along, d_t1z), d, out.d_t1[2].data() + bin);
      hn::StoreU(hn::Mul(twice_across, d_t2x), d, out.d_t2[0].data() + bin);
      hn::StoreU(hn::Mul(twice_across, d_t2y), d, out.d_t2[1].data() + bin);
      hn::StoreU(hn::Mul(twice_across, d_t2z), d, out.d_t2[2].data() + bin);
      hn::StoreU(hn::Neg(d_px), d, out.d_p[0].data() + bin);
      hn::StoreU(hn::Neg(d_py), d, out.d_p[1].data() + bin);
      hn::StoreU(hn::Neg(d_pz), d, out.d_p[2].data() + bin);
    }
  }
}

void AverageOverBins(const LobeTerms& lobe, const BinNodes& nodes, bool want_jacobian,
                     BinAverages& out) {
  if (want_jacobian) {
    average_over_bins<true>(lobe, nodes, out);
  } else {
    average_over_bins<false>(lobe, nodes, out);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace scatterlab::fit
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace scatterlab::fit {

HWY_EXPORT(AverageOverBins);

BinNodes::BinNodes(const LobeGrid& grid) : bins(grid.size()), slots(grid.nodes_per_bin()) {
  // A multiple of the widest vector of any target (256 bytes: SVE, RVV); this part of the file
  // sees only the baseline target's HWY_MAX_BYTES.
  constexpr std::size_t widest = 256 / sizeof(double);
  padded_bins = (bins + widest - 1) / widest * widest;
  for (std::vector<double>* values : {&x, &y, &z, &weight})
    values->assign(slots * padded_bins, 0.0);
  for (std::size_t q = 0; q < slots; ++q) {
    for (std::size_t bin = 0; bin < padded_bins; ++bin) {
      const std::size_t at = q * padded_bins + bin;
      if (bin < bins) {
        const LobeNode& node = grid.nodes(bin)[q];
        x[at] = node.direction.x(), y[at] = node.direction.y(), z[at] = node.direction.z();
        weight[at] = node.weight;
      } else {
        z[at] = 1.0;  // a direction, so that l stays finite
      }
    }
  }
}

void average_over_bins(const LobeTerms& lobe, const BinNodes& nodes, bool want_jacobian,
                       BinAverages& out) {
  for (std::vector<double>* values :
       {&out.scale, &out.sum, &out.ramp, &out.ramp_gamma, &out.along, &out.across, &out.d_t1[0],
        &out.d_t1[1], &out.d_t1[2], &out.d_t2[0], &out.d_t2[1], &out.d_t2[2], &out.d_p[0],
        &out.d_p[1], &out.d_p[2]}) {
    values->resize(nodes.padded_bins);
  }
  HWY_DYNAMIC_DISPATCH(AverageOverBins)(lobe, nodes, want_jacobian, out);
}

}  // namespace scatterlab::fit
#endif  // HWY_ONCE
