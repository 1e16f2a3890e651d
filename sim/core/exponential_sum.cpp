// ExponentialSum (exponential_sum.hpp), compiled once per instruction set by Highway's
// foreach_target (this file includes itself through HWY_TARGET_INCLUDE) and dispatched at run
// time.
#include "scatterlab/core/exponential_sum.hpp"

#include <cstddef>
#include <stdexcept>

// Highway's order: foreach_target, then highway.h, then its -inl.h headers.
// clang-format off
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/core/exponential_sum.cpp"
#include <hwy/foreach_target.h>
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>
// clang-format on

HWY_BEFORE_NAMESPACE();
namespace scatterlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

double SumExponentials(const double* weights, const double* rates, std::size_t size, double x) {
  const hn::ScalableTag<double> d;
  const std::size_t n = hn::Lanes(d);
  const auto minus_x = hn::Set(d, -x);
  auto sum = hn::Zero(d);
  for (std::size_t k = 0; k < size; k += n) {
    const auto term = hn::Exp(d, hn::Mul(minus_x, hn::LoadU(d, rates + k)));
    sum = hn::MulAdd(hn::LoadU(d, weights + k), term, sum);
  }
  return hn::GetLane(hn::SumOfLanes(d, sum));
}

}  // namespace HWY_NAMESPACE
}  // namespace scatterlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace scatterlab {

HWY_EXPORT(SumExponentials);

ExponentialSum::ExponentialSum(std::span<const double> weights, std::span<const double> rates) {
  if (weights.size() != rates.size()) {
    throw std::invalid_argument("ExponentialSum: as many weights as rates");
  }
  // A multiple of the widest vector of any target (256 bytes: SVE, RVV); this part of the file
  // sees only the baseline target's HWY_MAX_BYTES.
  constexpr std::size_t widest = 256 / sizeof(double);
  const std::size_t padded = (weights.size() + widest - 1) / widest * widest;
  weights_.assign(weights.begin(), weights.end());
  rates_.assign(rates.begin(), rates.end());
  weights_.resize(padded, 0.0);
  rates_.resize(padded, 0.0);
}

double ExponentialSum::operator()(double x) const {
  return HWY_DYNAMIC_DISPATCH(SumExponentials)(weights_.data(), rates_.data(), weights_.size(), x);
}

}  // namespace scatterlab
#endif  // HWY_ONCE
