// The half-space searchlight (transport/searchlight): totals against Chandrasekhar's exact
// diffuse reflectance, the once-scattered part against its closed form with and without a
// Fresnel interface, energy balance over extreme scenes, and the identities that tie the tallies
// together (fixed seeds; k sigma tolerances).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/fresnel.hpp"
#include "scatterlab/core/quadrature.hpp"
#include "scatterlab/models/chandrasekhar_h.hpp"
#include "scatterlab/refract/half_space_single_scatter.hpp"
#include "scatterlab/transport/searchlight.hpp"

namespace scatterlab {
namespace {

const TallyResult& find(const TransportOutput& out, const std::string& name) {
  for (const TallyResult& t : out.tallies) {
    if (t.name == name) return t;
  }
  ADD_FAILURE() << "no tally named " << name;
  static const TallyResult none{"", {}, {}, "", "", {0.0}, {0.0}};
  return none;
}
double value(const TransportOutput& out, const std::string& name) {
  return find(out, name).mean.at(0);
}
double error(const TransportOutput& out, const std::string& name) {
  return find(out, name).stderr_of_mean.at(0);
}

HalfSpaceSpec scene(double albedo, double g, double eta, std::uint64_t photons) {
  HalfSpaceSpec spec;
  spec.medium.albedo = albedo;
  spec.medium.g = g;
  spec.eta = eta;
  spec.run.photons = photons;
  spec.run.batches = 32;
  spec.run.threads = 2;
  spec.grid.r.bins = 40;
  spec.grid.z.bins = 20;
  spec.grid.theta_o.bins = 6;
  spec.tallies.fluence = false;
  return spec;
}

double energy_total(const TransportOutput& out, const HalfSpaceSpec& spec) {
  double total = value(out, "specular_reflectance") + value(out, "diffuse_reflectance") +
                 value(out, "absorbed");
  if (std::isfinite(spec.run.escape_radius)) total += value(out, "escaped");
  return total;
}

// Once-scattered diffuse reflectance, exact for isotropic scattering: entering along mu_t with
// power T, the first collision at path s (density e^-s, depth mu_t s) scatters with probability
// w into an upward cosine mu (density 1/2), reaches the surface with probability
// e^{-mu_t s / mu} and leaves with 1 - F(mu, 1/eta); reflected light only goes deeper. So
//   R_1 = T (w / 2) int_0^1 mu / (mu + mu_t) (1 - F(mu, 1 / eta)) dmu.
double single_scatter_reflectance(double albedo, double eta, double incidence_deg) {
  const double cos_i = std::cos(incidence_deg * std::numbers::pi / 180.0);
  const FresnelDielectric entry = fresnel_dielectric_terms(cos_i, eta);
  const double mu_t = entry.cos_transmitted;
  const auto integrand = [eta, mu_t](double mu) {
    return mu / (mu + mu_t) * fresnel_dielectric_transmittance(mu, 1.0 / eta);
  };
  // The critical cosine, where 1 - F has a kink, starts the subdivision.
  const double critical = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.5;
  const double breaks[] = {0.0, critical, 1.0};
  return (1.0 - entry.reflectance()) * 0.5 * albedo * integrate_adaptive(integrand, breaks).value;
}

TEST(Searchlight, DiffuseReflectanceMatchesChandrasekharWhenIndexMatched) {
  // 1e6 photons per albedo, normal incidence: R = 1 - H(1) sqrt(1 - w).
  for (double albedo : {0.3, 0.7, 0.9, 0.99}) {
    const TransportOutput out = run_half_space(scene(albedo, 0.0, 1.0, 1'000'000));
    const double exact = half_space_diffuse_reflectance(albedo);
    const double sigma = error(out, "diffuse_reflectance");
    EXPECT_NEAR(value(out, "diffuse_reflectance"), exact, 4.0 * sigma) << "albedo " << albedo;
    EXPECT_LT(sigma, 6e-4);  // the check has teeth
    EXPECT_EQ(value(out, "specular_reflectance"), 0.0);
  }
}

TEST(Searchlight, ObliqueIndexMatchedReflectanceMatchesChandrasekhar) {
  HalfSpaceSpec spec = scene(0.9, 0.0, 1.0, 500'000);
  spec.incidence_deg = 60.0;  // mu0 = 1/2
  const TransportOutput out = run_half_space(spec);
  EXPECT_NEAR(value(out, "diffuse_reflectance"), half_space_diffuse_reflectance(0.9, 0.5),
              4.0 * error(out, "diffuse_reflectance"));
}

TEST(Searchlight, OnceScatteredReflectanceMatchesItsClosedForm) {
  struct Case {
    double eta, incidence;
  };
  for (const Case c :
       {Case{1.0, 0.0}, Case{1.33, 0.0}, Case{1.33, 50.0}, Case{2.5, 0.0}, Case{0.75, 30.0}}) {
    HalfSpaceSpec spec = scene(0.8, 0.0, c.eta, 400'000);
    spec.incidence_deg = c.incidence;
    const TransportOutput out = run_half_space(spec);
    const double exact = single_scatter_reflectance(0.8, c.eta, c.incidence);
    EXPECT_NEAR(value(out, "diffuse_reflectance_single"), exact,
                4.0 * error(out, "diffuse_reflectance_single"))
        << "eta " << c.eta << ", incidence " << c.incidence;
    EXPECT_EQ(value(out, "diffuse_reflectance_unscattered"), 0.0);
    const double cos_i = std::cos(c.incidence * std::numbers::pi / 180.0);
    EXPECT_DOUBLE_EQ(value(out, "specular_reflectance"),
                     fresnel_dielectric_reflectance(cos_i, c.eta));
  }
}

TEST(Searchlight, OnceScatteredProfileMatchesTheExactSingleScatterSolution) {
  // R_1(r) per ring from the refractive single-scatter solution (refract/) for an anisotropic
  // medium behind a Fresnel interface: every ring within 4 sigma, and the total.
  HalfSpaceSpec spec = scene(0.9, 0.5, 1.33, 400'000);
  spec.grid.r = {0.0, 1.5, 15};  // once-scattered light leaves within a few tenths of a mfp
  const TransportOutput out = run_half_space(spec);
  const std::vector<double> edges = spec.grid.r.edges();
  const SingleScatterReflectance exact =
      half_space_single_scatter_reflectance(spec.medium, spec.eta, edges);
  const TallyResult& single = find(out, "reflectance_single");
  for (std::size_t i = 0; i < single.size(); ++i) {
    EXPECT_NEAR(single.mean[i], exact.mean[i], 4.0 * single.stderr_of_mean[i] + exact.error[i])
        << "ring " << i;
  }
  for (std::size_t i = 0; i < 4; ++i) {  // the check has teeth where most of R_1 is
    EXPECT_LT(single.stderr_of_mean[i], 0.05 * exact.mean[i]) << "ring " << i;
  }
  EXPECT_NEAR(value(out, "diffuse_reflectance_single"), exact.total,
              4.0 * error(out, "diffuse_reflectance_single"));
}

TEST(Searchlight, EnergyBalancesAndNothingIsNaNInExtremeScenes) {
  struct Case {
    double albedo, g, eta, incidence;
    std::uint64_t photons;
  };
  const Case cases[] = {
      {0.0, 0.0, 1.33, 0.0, 20000},     {1e-6, 0.5, 2.5, 10.0, 20000},
      {0.9999, 0.0, 1.0, 0.0, 3000},    {0.9999, 0.0, 2.5, 0.0, 2000},
      {0.9, 0.999, 1.33, 0.0, 5000},    {0.9, -0.999, 1.33, 0.0, 20000},
      {0.99, 0.0, 1.0001, 45.0, 20000}, {0.99, 0.9, 0.75, 0.0, 20000},
      {0.99, 0.0, 0.75, 80.0, 20000},  // beyond the critical angle: nothing enters
      {0.5, -0.5, 1.33, 89.9, 20000},
  };
  for (const Case& c : cases) {
    HalfSpaceSpec spec = scene(c.albedo, c.g, c.eta, c.photons);
    spec.incidence_deg = c.incidence;
    spec.tallies.fluence = true;
    const TransportOutput out = run_half_space(spec);
    const std::string label = "albedo " + std::to_string(c.albedo) + ", g " + std::to_string(c.g) +
                              ", eta " + std::to_string(c.eta) + ", incidence " +
                              std::to_string(c.incidence);
    for (const TallyResult& t : out.tallies) {
      for (std::size_t i = 0; i < t.size(); ++i) {
        ASSERT_TRUE(std::isfinite(t.mean[i]) && std::isfinite(t.stderr_of_mean[i]))
            << t.name << "[" << i << "] " << label;
        ASSERT_GE(t.mean[i], 0.0) << t.name << "[" << i << "] " << label;
      }
    }
    // Analog transport: every entering photon ends in exactly one of exit or absorption.
    EXPECT_NEAR(energy_total(out, spec), 1.0, 1e-12) << label;
  }
  // eta < 1 beyond the critical angle asin(0.75) = 48.6 deg: the beam is reflected whole.
  HalfSpaceSpec spec = scene(0.99, 0.0, 0.75, 1000);
  spec.incidence_deg = 80.0;
  const TransportOutput out = run_half_space(spec);
  EXPECT_EQ(value(out, "specular_reflectance"), 1.0);
  EXPECT_EQ(value(out, "diffuse_reflectance"), 0.0);
}

TEST(Searchlight, ConservativeMediumNeedsAnEscapeRadiusAndThenBalances) {
  HalfSpaceSpec spec = scene(1.0, 0.0, 1.33, 2000);
  EXPECT_THROW(spec.validate(), InputError);
  spec.run.escape_radius = 30.0;
  const TransportOutput out = run_half_space(spec);
  EXPECT_EQ(value(out, "absorbed"), 0.0);
  EXPECT_NEAR(energy_total(out, spec), 1.0, 1e-12);
  EXPECT_GT(value(out, "escaped"), 0.0);
}

TEST(Searchlight, OrdersSumToTheTotalAndSurfaceTalliesAgree) {
  HalfSpaceSpec spec = scene(0.9, 0.5, 1.33, 200'000);
  spec.grid.r.max = 40.0;  // wide enough to hold nearly every exit
  spec.tallies.fluence = true;
  const TransportOutput out = run_half_space(spec);
  for (const char* name : {"reflectance", "exitant_radiance", "fluence", "diffuse_reflectance"}) {
    const TallyResult& all = find(out, name);
    const TallyResult& zero = find(out, std::string(name) + "_unscattered");
    const TallyResult& one = find(out, std::string(name) + "_single");
    const TallyResult& many = find(out, std::string(name) + "_multiple");
    for (std::size_t i = 0; i < all.size(); ++i) {
      EXPECT_NEAR(zero.mean[i] + one.mean[i] + many.mean[i], all.mean[i], 1e-12 * (1 + all.mean[i]))
          << name << "[" << i << "]";
      if (std::string(name) != "fluence") {
        EXPECT_EQ(zero.mean[i], 0.0);
      }
    }
  }
  // R_d(r) over the surface, and the radiance over projected solid angle per ring.
  const TallyResult& reflectance = find(out, "reflectance");
  const TallyResult& radiance = find(out, "exitant_radiance");
  const UniformAxis& r = spec.grid.r;
  const UniformAxis& theta = spec.grid.theta_o;
  double on_surface = 0.0;
  for (std::size_t i = 0; i < reflectance.size(); ++i) {
    const double r0 = r.edge(static_cast<int>(i)), r1 = r.edge(static_cast<int>(i) + 1);
    on_surface += reflectance.mean[i] * std::numbers::pi * (r1 * r1 - r0 * r0);
    double from_radiance = 0.0;
    for (std::size_t k = 0; k < radiance.shape[1]; ++k) {
      const double s0 = std::sin(theta.edge(static_cast<int>(k)));
      const double s1 = std::sin(theta.edge(static_cast<int>(k) + 1));
      from_radiance +=
          radiance.mean[i * radiance.shape[1] + k] * std::numbers::pi * (s1 * s1 - s0 * s0);
    }
    EXPECT_NEAR(from_radiance, reflectance.mean[i], 1e-12 * (1.0 + reflectance.mean[i]));
  }
  // Exits beyond 40 mfp at albedo 0.9 are below 1e-6 of the total.
  EXPECT_NEAR(on_surface, value(out, "diffuse_reflectance"), 1e-6);
}

TEST(Searchlight, AbsorptionFromTheFluenceMatchesTheAbsorbedPower) {
  // integral of sigma_a phi dV over a grid that holds nearly all of it = absorbed, 4 sigma.
  HalfSpaceSpec spec = scene(0.5, 0.0, 1.33, 400'000);
  spec.grid.r = {0.0, 20.0, 40};
  spec.grid.z = {0.0, 20.0, 40};
  spec.tallies.fluence = true;
  const TransportOutput out = run_half_space(spec);
  const TallyResult& fluence = find(out, "fluence");
  double absorbed = 0.0, bound = 0.0;
  for (std::size_t i = 0; i < fluence.size(); ++i) {
    const int ir = static_cast<int>(i / fluence.shape[1]);
    const double r0 = spec.grid.r.edge(ir), r1 = spec.grid.r.edge(ir + 1);
    const double volume = std::numbers::pi * (r1 * r1 - r0 * r0) * spec.grid.z.width();
    absorbed += 0.5 * fluence.mean[i] * volume;
    bound += 0.5 * fluence.stderr_of_mean[i] * volume;  // correlated cells: add linearly
  }
  EXPECT_NEAR(absorbed, value(out, "absorbed"), 4.0 * (bound + error(out, "absorbed")));
  EXPECT_LT(bound, 0.01);
  // The unscattered fluence along the axis integrates to T (1 - e^{-z_max}) collisions.
  const TallyResult& direct = find(out, "fluence_unscattered");
  double direct_collisions = 0.0, direct_bound = 0.0;
  for (std::size_t iz = 0; iz < direct.shape[1]; ++iz) {
    const double volume =
        std::numbers::pi * spec.grid.r.width() * spec.grid.r.width() * spec.grid.z.width();
    direct_collisions += direct.mean[iz] * volume;
    direct_bound += direct.stderr_of_mean[iz] * volume;
  }
  const double transmitted = 1.0 - value(out, "specular_reflectance");
  EXPECT_NEAR(direct_collisions, transmitted * (1.0 - std::exp(-20.0)), 4.0 * direct_bound);
}

TEST(Searchlight, ExitanceMapIsTheSurfaceSeenFromAbove) {
  // One cell holding the whole surface: the map times its area is the diffuse reflectance, photon
  // for photon.
  HalfSpaceSpec whole = scene(0.9, 0.5, 1.3, 20'000);
  whole.tallies.exitance_map = true;
  whole.grid.x = {-1e4, 1e4, 1};
  whole.grid.y = {-1e4, 1e4, 1};
  const TransportOutput all = run_half_space(whole);
  EXPECT_NEAR(find(all, "exitance_map").mean.at(0) * 4e8, value(all, "diffuse_reflectance"), 1e-12);

  // Sums of the map over parts of the surface, with the sum of the cells' variances (an upper
  // bound on the variance of a sum of counts that exclude each other photon by photon).
  const auto part = [](const TallyResult& map, int bins, auto&& in) {
    double sum = 0.0, variance = 0.0;
    for (int i = 0; i < bins; ++i) {
      for (int j = 0; j < bins; ++j) {
        if (!in(i, j)) continue;
        const auto k = static_cast<std::size_t>(i * bins + j);
        sum += map.mean[k];
        variance += map.stderr_of_mean[k] * map.stderr_of_mean[k];
      }
    }
    return std::pair{sum, std::sqrt(variance)};
  };
  const int bins = 8;
  // Normal incidence: the four quadrants about the entry point hold the same light.
  HalfSpaceSpec normal = scene(0.9, 0.5, 1.3, 200'000);
  normal.tallies.exitance_map = true;
  normal.grid.x = {-2.0, 2.0, bins};
  normal.grid.y = {-2.0, 2.0, bins};
  const TransportOutput normal_out = run_half_space(normal);
  const TallyResult& square = find(normal_out, "exitance_map");
  const auto q1 = part(square, bins, [](int i, int j) { return i >= 4 && j >= 4; });
  for (const auto& [name, quadrant] :
       {std::pair{"-x +y", part(square, bins, [](int i, int j) { return i < 4 && j >= 4; })},
        std::pair{"-x -y", part(square, bins, [](int i, int j) { return i < 4 && j < 4; })},
        std::pair{"+x -y", part(square, bins, [](int i, int j) { return i >= 4 && j < 4; })}}) {
    EXPECT_NEAR(quadrant.first, q1.first, 4.0 * std::hypot(quadrant.second, q1.second)) << name;
  }
  // A beam at 60 degrees in the x-z plane: mirror images about y = 0, and more light on the side
  // it travels towards (+x) than behind it.
  HalfSpaceSpec oblique = normal;
  oblique.incidence_deg = 60.0;
  const TransportOutput oblique_out = run_half_space(oblique);
  const TallyResult& halo = find(oblique_out, "exitance_map");
  const auto above = part(halo, bins, [](int, int j) { return j >= 4; });
  const auto below = part(halo, bins, [](int, int j) { return j < 4; });
  EXPECT_NEAR(above.first, below.first, 4.0 * std::hypot(above.second, below.second));
  const auto ahead = part(halo, bins, [](int i, int) { return i >= 4; });
  const auto behind = part(halo, bins, [](int i, int) { return i < 4; });
  EXPECT_GT(ahead.first - behind.first, 10.0 * std::hypot(ahead.second, behind.second));
}

TEST(Searchlight, SameResultForAnyThreadCount) {
  HalfSpaceSpec spec = scene(0.9, 0.3, 1.33, 20000);
  spec.tallies.fluence = true;
  spec.run.threads = 1;
  const TransportOutput one = run_half_space(spec);
  spec.run.threads = 2;
  const TransportOutput two = run_half_space(spec);
  ASSERT_EQ(one.tallies.size(), two.tallies.size());
  for (std::size_t t = 0; t < one.tallies.size(); ++t) {
    EXPECT_EQ(one.tallies[t].mean, two.tallies[t].mean) << one.tallies[t].name;
    EXPECT_EQ(one.tallies[t].stderr_of_mean, two.tallies[t].stderr_of_mean);
  }
}

TEST(Searchlight, RejectsBadInputNamingTheField) {
  const auto field_of = [](HalfSpaceSpec spec) {
    try {
      spec.validate();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  HalfSpaceSpec spec;
  EXPECT_EQ(field_of(spec), "(accepted)");
  spec.eta = 0.0;
  EXPECT_EQ(field_of(spec), "surface.eta");
  spec = {};
  spec.eta = std::nan("");
  EXPECT_EQ(field_of(spec), "surface.eta");
  spec = {};
  spec.incidence_deg = 90.0;
  EXPECT_EQ(field_of(spec), "source.incidence_deg");
  spec = {};
  spec.medium.albedo = 1.2;
  EXPECT_EQ(field_of(spec), "medium.albedo");
  spec = {};
  spec.grid.r.max = 0.0;
  EXPECT_EQ(field_of(spec), "grid.r.max");
  spec = {};
  spec.run.batches = 1;
  EXPECT_EQ(field_of(spec), "run.batches");
}

}  // namespace
}  // namespace scatterlab
