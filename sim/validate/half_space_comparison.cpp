#include "scatterlab/validate/half_space_comparison.hpp"

#include <cmath>
#include <limits>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/medium.hpp"
#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/photon_beam_diffusion.hpp"
#include "scatterlab/models/quantized_diffusion.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"

namespace scatterlab {
namespace {

// Mean relative error against the Monte Carlo of the curve's part over resolved bins; `is_near`
// tells a bin's range.
template <typename IsNear>
void score(ModelCurve& curve, const std::map<ModelPart, MonteCarloCurve>& mc_by_part,
           IsNear is_near) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto found = mc_by_part.find(curve.part);
  if (found == mc_by_part.end()) {
    curve.near_error = curve.far_error = nan;
    return;
  }
  const MonteCarloCurve& mc = found->second;
  double near = 0.0, far = 0.0;
  int n_near = 0, n_far = 0;
  for (std::size_t i = 0; i < curve.values.size(); ++i) {
    if (!(mc.mean[i] > 3.0 * mc.stderr_of_mean[i]) || !(mc.mean[i] > 0.0)) continue;
    const double e = std::abs(curve.values[i] - mc.mean[i]) / mc.mean[i];
    if (is_near(i)) {
      near += e, ++n_near;
    } else {
      far += e, ++n_far;
    }
  }
  curve.near_error = n_near ? near / n_near : nan;
  curve.far_error = n_far ? far / n_far : nan;
}

void check_mc(const std::map<ModelPart, MonteCarloCurve>& mc_by_part, std::size_t bins,
              const std::string& what) {
  for (const auto& [part, mc] : mc_by_part) {
    if (mc.mean.size() != bins || mc.stderr_of_mean.size() != bins) {
      throw InputError("monte_carlo",
                       what + tally_suffix(part) + " has " + std::to_string(mc.mean.size()) + " bins",
                       std::to_string(bins) + " bins (mean and stderr), as the model grid");
    }
  }
}

std::vector<double> scaled(std::vector<double> v, double factor) {
  for (double& x : v) x *= factor;
  return v;
}

ModelCurve curve(std::string model, ModelPart part, std::vector<double> values, double total = 0.0) {
  ModelCurve c;
  c.model = std::move(model);
  c.part = part;
  c.values = std::move(values);
  c.total = total;
  return c;
}

std::vector<double> sum(std::vector<double> a, const std::vector<double>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
  return a;
}

}  // namespace

std::string tally_suffix(ModelPart part) {
  switch (part) {
    case ModelPart::single: return "_single";
    case ModelPart::multiple: return "_multiple";
    case ModelPart::all: return "";
  }
  return "";
}

HalfSpaceComparison compare_half_space(const HalfSpaceMedium& medium, double entry_transmittance,
                                       std::span<const double> r_edges,
                                       std::span<const double> z_edges,
                                       std::map<ModelPart, MonteCarloCurve> reflectance_mc,
                                       std::map<ModelPart, MonteCarloCurve> fluence_mc,
                                       double near_limit) {
  medium.validate();
  if (!(entry_transmittance >= 0.0 && entry_transmittance <= 1.0)) {
    throw InputError("entry_transmittance", "got " + std::to_string(entry_transmittance), "[0, 1]");
  }
  HalfSpaceComparison c;
  c.medium = medium;
  c.entry_transmittance = entry_transmittance;
  c.near_limit = near_limit;
  c.r_edges.assign(r_edges.begin(), r_edges.end());
  c.z_edges.assign(z_edges.begin(), z_edges.end());
  const std::size_t nr = r_edges.size() > 0 ? r_edges.size() - 1 : 0;
  const std::size_t nz = z_edges.size() > 0 ? z_edges.size() - 1 : 0;
  check_mc(reflectance_mc, nr, "reflectance");
  check_mc(fluence_mc, nr * nz, "fluence");
  c.reflectance_mc = std::move(reflectance_mc);
  c.fluence_mc = std::move(fluence_mc);
  const double t = entry_transmittance;

  // The exact once-scattered light of the real medium (HG g), already per unit incident power.
  const SingleScatterReflectance single = half_space_single_scatter_reflectance(
      Medium::from_coefficients(medium.sigma_a, medium.sigma_s, medium.g, "mfp"), medium.eta,
      r_edges, 1e-8);
  c.reflectance.push_back(curve("single_scatter", ModelPart::single, single.mean, single.total));
  c.reflectance.back().error = single.error;
  c.reflectance.back().total_error = single.total_error;

  const DipoleModel dipole = classical_dipole(medium);
  const DipoleModel better = better_dipole(medium);
  const QuantizedDiffusion quantized = quantized_diffusion(medium);
  const GrosjeanBeam beam = grosjean_beam(medium);
  const PhotonBeamDiffusion photon_beam = photon_beam_diffusion(medium);
  const std::vector<ModelCurve> diffusion = {
      curve("dipole", ModelPart::multiple,
            scaled(dipole_reflectance_annulus_average(dipole, r_edges), t),
            t * dipole_total_reflectance(dipole)),
      curve("better_dipole", ModelPart::multiple,
            scaled(dipole_reflectance_annulus_average(better, r_edges), t),
            t * dipole_total_reflectance(better)),
      curve("quantized_diffusion", ModelPart::multiple,
            scaled(quantized_diffusion_reflectance_annulus_average(quantized, r_edges), t),
            t * quantized_diffusion_total_reflectance(quantized)),
      curve("photon_beam_diffusion", ModelPart::multiple,
            scaled(photon_beam_diffusion_annulus_average(photon_beam, r_edges), t),
            t * photon_beam_diffusion_total_reflectance(photon_beam)),
  };
  for (const ModelCurve& m : diffusion) c.reflectance.push_back(m);
  for (const ModelCurve& m : diffusion) {
    c.reflectance.push_back(curve(m.model + "+single_scatter", ModelPart::all,
                                  sum(m.values, single.mean), m.total + single.total));
  }
  for (const ModelPart part : {ModelPart::multiple, ModelPart::all}) {
    c.reflectance.push_back(
        curve("scatterlab_grosjean_beam", part,
              scaled(grosjean_beam_reflectance_annulus_average(beam, r_edges, part), t),
              t * grosjean_beam_total_reflectance(beam, part)));
  }
  for (ModelCurve& curve : c.reflectance) {
    score(curve, c.reflectance_mc, [&](std::size_t i) { return r_edges[i + 1] <= near_limit; });
  }

  if (nz > 0) {
    c.fluence = {
        curve("dipole", ModelPart::multiple,
              scaled(dipole_fluence_cell_average(dipole, r_edges, z_edges), t)),
        curve("better_dipole", ModelPart::multiple,
              scaled(dipole_fluence_cell_average(better, r_edges, z_edges), t)),
        curve("quantized_diffusion", ModelPart::multiple,
              scaled(quantized_diffusion_fluence_cell_average(quantized, r_edges, z_edges), t)),
        curve("scatterlab_grosjean_beam", ModelPart::all,
              scaled(grosjean_beam_fluence_cell_average(beam, r_edges, z_edges), t)),
    };
    // Near: cells whose far corner is within near_limit of the entry point.
    for (ModelCurve& curve : c.fluence) {
      score(curve, c.fluence_mc, [&](std::size_t k) {
        const double r1 = r_edges[k / nz + 1], z1 = z_edges[k % nz + 1];
        return std::hypot(r1, z1) <= near_limit;
      });
    }
  }
  return c;
}

}  // namespace scatterlab
