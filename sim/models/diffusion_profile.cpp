#include "scatterlab/models/diffusion_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "scatterlab/core/error.hpp"

namespace scatterlab {
namespace {

std::variant<DipoleModel, QuantizedDiffusion, RingProfile> model_terms(
    ProfileModel model, const HalfSpaceMedium& medium) {
  medium.validate();
  switch (model) {
    case ProfileModel::dipole:
      return classical_dipole(medium);
    case ProfileModel::better_dipole:
      return better_dipole(medium);
    case ProfileModel::quantized_diffusion:
      return quantized_diffusion(medium);
    case ProfileModel::measured:
      break;
  }
  throw std::logic_error("a measured profile is made from its rings");
}

RingProfile checked(RingProfile rings, const HalfSpaceMedium& medium) {
  medium.validate();
  const std::size_t n = rings.mean.size();
  bool ok = n >= 1 && rings.r_edges.size() == n + 1 && rings.stderr_of_mean.size() == n &&
            rings.r_edges.front() == 0.0;
  for (std::size_t i = 0; ok && i < n; ++i)
    ok = std::isfinite(rings.r_edges[i + 1]) && rings.r_edges[i + 1] > rings.r_edges[i] &&
         std::isfinite(rings.mean[i]) && std::isfinite(rings.stderr_of_mean[i]);
  if (!ok)
    throw InputError("rings", "not a ring profile",
                     "edges from 0, increasing and finite, one finite mean and standard error "
                     "per ring");
  return rings;
}

}  // namespace

std::string to_string(ProfileModel model) {
  switch (model) {
    case ProfileModel::dipole:
      return "dipole";
    case ProfileModel::better_dipole:
      return "better_dipole";
    case ProfileModel::quantized_diffusion:
      return "quantized_diffusion";
    case ProfileModel::measured:
      return "measured";
  }
  throw std::logic_error("unknown profile model");
}

int RingProfile::ring_of(double r) const {
  if (!(r >= 0.0) || r >= r_edges.back()) return -1;
  const auto upper = std::upper_bound(r_edges.begin() + 1, r_edges.end(), r);
  return static_cast<int>(upper - r_edges.begin()) - 1;
}

std::optional<ProfileModel> find_profile_model(std::string_view name) {
  for (ProfileModel model : all_profile_models)
    if (name == to_string(model)) return model;
  return std::nullopt;
}

ProfileModel parse_profile_model(std::string_view name, std::string_view field) {
  if (const std::optional<ProfileModel> model = find_profile_model(name)) return *model;
  throw InputError(std::string(field), "unknown model '" + std::string(name) + "'",
                   "dipole, better_dipole, quantized_diffusion");
}

DiffusionProfile::DiffusionProfile(ProfileModel model, const HalfSpaceMedium& medium)
    : model_(model), medium_(medium), model_terms_(model_terms(model, medium)) {}

DiffusionProfile::DiffusionProfile(RingProfile rings, const HalfSpaceMedium& medium)
    : model_(ProfileModel::measured),
      medium_(medium),
      model_terms_(checked(std::move(rings), medium)) {}

double DiffusionProfile::reflectance(double r) const {
  if (const RingProfile* measured = rings()) {
    const int ring = measured->ring_of(r);
    return ring < 0 ? 0.0 : measured->mean[ring];
  }
  if (const auto* dipole = std::get_if<DipoleModel>(&model_terms_))
    return dipole_reflectance(*dipole, r);
  return quantized_diffusion_reflectance(std::get<QuantizedDiffusion>(model_terms_), r);
}

double DiffusionProfile::total_reflectance() const {
  if (const RingProfile* measured = rings()) {
    const std::vector<double>& e = measured->r_edges;
    double total = 0.0;
    for (std::size_t i = 0; i < measured->mean.size(); ++i)
      total += measured->mean[i] * std::numbers::pi * (e[i + 1] * e[i + 1] - e[i] * e[i]);
    return total;
  }
  if (const auto* dipole = std::get_if<DipoleModel>(&model_terms_))
    return dipole_total_reflectance(*dipole);
  return quantized_diffusion_total_reflectance(std::get<QuantizedDiffusion>(model_terms_));
}

std::vector<double> DiffusionProfile::annulus_averages(std::span<const double> r_edges) const {
  if (const RingProfile* measured = rings()) {
    // Constant on each ring: the average over an annulus is the rings' area-weighted mean.
    const std::vector<double>& e = measured->r_edges;
    std::vector<double> averages(r_edges.size() - 1, 0.0);
    for (std::size_t a = 0; a + 1 < r_edges.size(); ++a) {
      double sum = 0.0;
      for (std::size_t i = 0; i < measured->mean.size(); ++i) {
        const double lo = std::max(e[i], r_edges[a]), hi = std::min(e[i + 1], r_edges[a + 1]);
        if (hi > lo) sum += measured->mean[i] * (hi * hi - lo * lo);
      }
      const double area = r_edges[a + 1] * r_edges[a + 1] - r_edges[a] * r_edges[a];
      averages[a] = area > 0.0 ? sum / area : 0.0;
    }
    return averages;
  }
  if (const auto* dipole = std::get_if<DipoleModel>(&model_terms_))
    return dipole_reflectance_annulus_average(*dipole, r_edges);
  return quantized_diffusion_reflectance_annulus_average(std::get<QuantizedDiffusion>(model_terms_),
                                                         r_edges);
}

RadialProfileSampler::RadialProfileSampler(const DiffusionProfile& profile, double r_max,
                                           int cells) {
  if (!(r_max > 0.0) || !std::isfinite(r_max))
    throw InputError("r_max", "must be finite and > 0", "a radius > 0");
  if (cells < 2) throw InputError("cells", "too few cells", "at least 2");
  // Geometric cells follow the profile's 1/r^3 tails and its near-source peak alike; the first
  // cell, [0, 1e-6 r_max], holds what the near-source singularity (quantized diffusion) carries.
  edges_.resize(static_cast<std::size_t>(cells) + 1);
  edges_[0] = 0.0;
  const double first = 1e-6 * r_max;
  const double ratio = std::pow(r_max / first, 1.0 / (cells - 1));
  for (int i = 1; i <= cells; ++i) edges_[i] = first * std::pow(ratio, i - 1);
  edges_[cells] = r_max;
  const std::vector<double> averages = profile.annulus_averages(edges_);
  cdf_.assign(edges_.size(), 0.0);
  for (int i = 0; i < cells; ++i) {
    const double area = std::numbers::pi * (edges_[i + 1] * edges_[i + 1] - edges_[i] * edges_[i]);
    cdf_[i + 1] = cdf_[i] + std::max(averages[i], 0.0) * area;
  }
  total_ = cdf_.back();
  if (!(total_ > 0.0) || !std::isfinite(total_))
    throw InputError("medium", "the profile carries no light within r_max",
                     "a medium that scatters (albedo > 0)");
  for (double& c : cdf_) c /= total_;
}

double RadialProfileSampler::sample(double u, double& density) const {
  const auto upper = std::upper_bound(cdf_.begin() + 1, cdf_.end() - 1, u);
  const std::size_t i = static_cast<std::size_t>(upper - cdf_.begin()) - 1;
  const double weight = cdf_[i + 1] - cdf_[i];
  const double width = edges_[i + 1] - edges_[i];
  density = weight / width;
  const double t = weight > 0.0 ? (u - cdf_[i]) / weight : 0.5;
  return std::min(edges_[i] + std::clamp(t, 0.0, 1.0) * width, edges_[i + 1]);
}

double RadialProfileSampler::density(double r) const {
  if (r < 0.0 || r > edges_.back()) return 0.0;
  const auto upper = std::upper_bound(edges_.begin() + 1, edges_.end() - 1, r);
  const std::size_t i = static_cast<std::size_t>(upper - edges_.begin()) - 1;
  return (cdf_[i + 1] - cdf_[i]) / (edges_[i + 1] - edges_[i]);
}

}  // namespace scatterlab
