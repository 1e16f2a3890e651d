#pragma once
// A radial profile R_d(r) of the searchlight problem (Bitterli §2.3, eq. 2.15): the exitance at
// distance r from where a unit power enters a half-space, for each published diffusion model
// (classical dipole, better dipole: dipole.hpp; quantized diffusion: quantized_diffusion.hpp),
// held behind one type so that a BSSRDF (bssrdf.hpp) or a renderer can take any of them.
//
// Besides the models, a profile can be measured: R_d averaged over rings (the searchlight Monte
// Carlo's multiply-scattered part, per unit power entering), constant on each ring and 0 beyond
// the last. A BSSRDF built on it carries no diffusion-theory error, only the BSSRDF's own (the
// planar profile used on another surface, the direction of entry ignored).
//
// Units: r in the medium's length unit, R_d in 1 / length^2 per unit power that entered the
// medium (the entry Fresnel loss is not in it; the BSSRDF's F_t(omega_i) is).
//
// RadialProfileSampler draws r with a density that follows 2 pi r R_d(r) on [0, r_max]: the
// importance sampling of the surface integrals of a BSSRDF (the lit sphere,
// lit_sphere_exitance.hpp), unbiased for any profile because it returns the exact density of what
// it draws.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scatterlab/models/dipole.hpp"
#include "scatterlab/models/half_space_medium.hpp"
#include "scatterlab/models/quantized_diffusion.hpp"

namespace scatterlab {

enum class ProfileModel { dipole, better_dipole, quantized_diffusion, measured };

// "dipole", "better_dipole", "quantized_diffusion", "measured"; parse_profile_model accepts the
// published models only, and throws InputError naming `field` and them otherwise.
std::string to_string(ProfileModel model);
ProfileModel parse_profile_model(std::string_view name, std::string_view field);
// The published model of that name, or none (for callers that accept other names too).
std::optional<ProfileModel> find_profile_model(std::string_view name);
inline constexpr ProfileModel all_profile_models[] = {
    ProfileModel::dipole, ProfileModel::better_dipole, ProfileModel::quantized_diffusion};

// A measured profile: mean and standard error of R_d on the rings between consecutive edges.
struct RingProfile {
  std::vector<double> r_edges;               // finite, >= 0, increasing; from 0
  std::vector<double> mean, stderr_of_mean;  // per ring, 1 / length^2 per unit power entering

  // The ring holding r, or -1 beyond the last edge.
  int ring_of(double r) const;
};

class DiffusionProfile {
 public:
  // medium.validate() first (InputError naming the field: eta in [0.5, 2.5], ...). `model` is a
  // published one (not measured).
  DiffusionProfile(ProfileModel model, const HalfSpaceMedium& medium);
  // A measured profile (InputError "rings" when its sizes or edges are not as RingProfile says).
  DiffusionProfile(RingProfile rings, const HalfSpaceMedium& medium);

  ProfileModel model() const { return model_; }
  const HalfSpaceMedium& medium() const { return medium_; }
  // The rings of a measured profile; nullptr for a model.
  const RingProfile* rings() const { return std::get_if<RingProfile>(&model_terms_); }
  // R_d(r), r >= 0; quantized diffusion is +infinity at r = 0 (its cell averages are finite).
  double reflectance(double r) const;
  // R_dr = int_0^inf R_d(r) 2 pi r dr, in closed form (a measured profile: its rings' sum).
  double total_reflectance() const;
  // Averages of R_d over the annuli between consecutive edges, in closed form (edges finite,
  // >= 0 and increasing; InputError "r_edges" otherwise).
  std::vector<double> annulus_averages(std::span<const double> r_edges) const;

 private:
  ProfileModel model_;
  HalfSpaceMedium medium_;
  std::variant<DipoleModel, QuantizedDiffusion, RingProfile> model_terms_;
};

// Draws r in [0, r_max] with a piecewise-constant density in r whose cell weights are the cell
// integrals of 2 pi r R_d(r) (closed form), on cells geometric from 1e-6 r_max to r_max, plus
// [0, 1e-6 r_max]. The density of a drawn r is exact for the piecewise-
// constant law, so f(r) / density(r) is an unbiased weight for any integrand f.
class RadialProfileSampler {
 public:
  RadialProfileSampler(const DiffusionProfile& profile, double r_max, int cells = 256);
  // r from one uniform u in (0, 1), and the density of r there (per unit length).
  double sample(double u, double& density) const;
  double density(double r) const;
  double r_max() const { return edges_.back(); }
  // int_0^r_max 2 pi r R_d dr, the sum of the cell weights.
  double integral() const { return total_; }

 private:
  std::vector<double> edges_;  // cells [edges_[i], edges_[i+1])
  std::vector<double> cdf_;    // cumulative weight at each edge, normalised to 1 at the end
  double total_ = 0.0;
};

}  // namespace scatterlab
