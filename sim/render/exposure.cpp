#include "scatterlab/render/exposure.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace scatterlab {
namespace {

double exposure_of(std::vector<double> values, double percentile) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(percentile * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  const double high = values[static_cast<std::size_t>(k)];
  return high > 0.0 && std::isfinite(high) ? -std::log2(high) : 0.0;
}

}  // namespace

double auto_exposure(const Image& image, double percentile) {
  std::vector<double> lit;
  for (const double v : image.values) {
    if (v > 0.0) lit.push_back(v);
  }
  return exposure_of(std::move(lit), percentile);
}

double auto_exposure(const RgbImage& image, double percentile) {
  std::vector<double> lit;
  for (std::size_t k = 0; k < image.channels[0].values.size(); ++k) {
    const double v = std::max(
        {image.channels[0].values[k], image.channels[1].values[k], image.channels[2].values[k]});
    if (v > 0.0) lit.push_back(v);
  }
  return exposure_of(std::move(lit), percentile);
}

}  // namespace scatterlab
