#include "scatterlab/tally/tally_layout.hpp"

#include <cmath>

#include "scatterlab/core/constants.hpp"

namespace scatterlab {
namespace {

std::size_t count(const UniformAxis& axis) { return static_cast<std::size_t>(axis.bins); }

// Volume of an annular cell r0 <= r < r1 of the uniform z grid, in mfp^3.
double ring_volume(const Grid& grid, std::size_t ir) {
  const double r0 = grid.r.edge(static_cast<int>(ir)), r1 = grid.r.edge(static_cast<int>(ir) + 1);
  return pi * (r1 * r1 - r0 * r0) * grid.z.width();
}

// Solid angle of a direction bin, in sr. A folded bin stands for phi and -phi together.
double bin_solid_angle(const Grid& grid, std::size_t itheta) {
  const int k = static_cast<int>(itheta);
  const double band = std::cos(grid.theta.edge(k)) - std::cos(grid.theta.edge(k + 1));
  return band * grid.phi.width() * (grid.fold_phi ? 2.0 : 1.0);
}

double shell_volume(const UniformAxis& rho, std::size_t i) {
  const double a = rho.edge(static_cast<int>(i)), b = rho.edge(static_cast<int>(i) + 1);
  return 4.0 / 3.0 * pi * (b * b * b - a * a * a);
}

const char* order_suffix(std::size_t block) {
  static const char* suffixes[] = {"", "_unscattered", "_single", "_multiple"};
  return suffixes[block];
}

const char* order_words(std::size_t block) {
  static const char* words[] = {"", " (unscattered light only)", " (once-scattered light only)",
                                " (light scattered twice or more)"};
  return words[block];
}

}  // namespace

TallyLayout::TallyLayout(const SimulationSpec& spec) {
  const Grid& grid = spec.grid;
  const TallyRequest& want = spec.tallies;
  r_bins = count(grid.r);
  z_bins = count(grid.z);
  theta_bins = count(grid.theta);
  phi_bins = count(grid.phi);
  rho_bins = count(grid.rho);

  std::size_t next = 0;
  auto place = [&next](bool wanted, std::size_t cells) {
    if (!wanted) return absent;
    const std::size_t at = next;
    next += cells;
    return at;
  };
  radiance = place(want.radiance, r_bins * z_bins * theta_bins * phi_bins);
  fluence = place(want.fluence, r_bins * z_bins);
  flux = place(want.flux, r_bins * z_bins * 2);
  fluence_spherical = place(want.fluence_spherical, rho_bins);
  block_size = next;
  split_by_order = want.split_by_order;
  scalars = block_size * (split_by_order ? 4 : 1);
  size = scalars + static_cast<std::size_t>(ScalarScore::count);
}

std::vector<TallyResult> finalize_tallies(const SimulationSpec& spec, const TallyLayout& layout,
                                          const std::vector<double>& raw_mean,
                                          const std::vector<double>& raw_stderr) {
  const Grid& grid = spec.grid;
  const std::string estimator =
      spec.tallies.estimator == Estimator::collision ? "collision estimator" : "track-length estimator";
  std::vector<TallyResult> results;

  // Copies the raw values from `offset`, dividing cell i by measure(i).
  auto add = [&](std::string name, std::vector<std::string> dims, std::vector<std::size_t> shape,
                 std::string units, std::string description, std::size_t offset,
                 auto&& measure) {
    results.push_back(measured_tally({std::move(name), std::move(dims), std::move(shape),
                                      std::move(units), std::move(description), {}, {}},
                                     raw_mean, raw_stderr, offset, measure));
  };

  const std::size_t blocks = layout.split_by_order ? 4 : 1;
  for (std::size_t block = 0; block < blocks; ++block) {
    const std::size_t base = block * layout.block_size;
    const std::string suffix = order_suffix(block);
    const std::string scope = order_words(block);
    if (layout.radiance != TallyLayout::absent) {
      const std::size_t angles = layout.theta_bins * layout.phi_bins;
      add("radiance" + suffix, {"r", "z", "theta", "phi"},
          {layout.r_bins, layout.z_bins, layout.theta_bins, layout.phi_bins},
          "W mfp^-2 sr^-1 per W incident",
          "radiance L(r, z, theta, phi), bin average, " + estimator + scope,
          base + layout.radiance, [&](std::size_t i) {
            const std::size_t cell = i / angles;
            const std::size_t itheta = (i % angles) / layout.phi_bins;
            return ring_volume(grid, cell / layout.z_bins) *
                   bin_solid_angle(grid, itheta);
          });
    }
    if (layout.fluence != TallyLayout::absent) {
      add("fluence" + suffix, {"r", "z"}, {layout.r_bins, layout.z_bins},
          "W mfp^-2 per W incident", "fluence phi(r, z), bin average, " + estimator + scope,
          base + layout.fluence, [&](std::size_t i) {
            return ring_volume(grid, i / layout.z_bins);
          });
    }
    if (layout.flux != TallyLayout::absent) {
      add("flux" + suffix, {"r", "z", "component"}, {layout.r_bins, layout.z_bins, 2},
          "W mfp^-2 per W incident",
          "vector irradiance E = integral of L omega d omega: components (E_r, E_z), " +
              estimator + scope,
          base + layout.flux, [&](std::size_t i) {
            const std::size_t cell = i / 2;
            return ring_volume(grid, cell / layout.z_bins);
          });
    }
    if (layout.fluence_spherical != TallyLayout::absent) {
      add("fluence_spherical" + suffix, {"rho"}, {layout.rho_bins}, "W mfp^-2 per W incident",
          "fluence phi(rho) on spherical shells about the source, shell average, " + estimator +
              scope,
          base + layout.fluence_spherical,
          [&](std::size_t i) { return shell_volume(grid.rho, i); });
    }
  }

  auto unit = [](std::size_t) { return 1.0; };
  auto scalar = [&](const char* name, ScalarScore s, const char* units, const char* description) {
    add(name, {}, {}, units, description, layout.scalar(s), unit);
  };
  scalar("absorbed", ScalarScore::absorbed, "W per W incident",
         "power absorbed inside the (r, z) grid");
  scalar("absorbed_outside_grid", ScalarScore::absorbed_outside_grid, "W per W incident",
         "power absorbed outside the (r, z) grid");
  if (std::isfinite(spec.run.escape_radius)) {
    scalar("escaped", ScalarScore::escaped, "W per W incident",
           "power carried past the escape radius (see /parameters escape_radius)");
  }
  scalar("absorbed_mean_depth", ScalarScore::absorption_depth, "mfp",
         "first moment of absorbed power along the beam axis, integral of z dA; the mean "
         "absorption depth when nothing escapes");
  return results;
}

}  // namespace scatterlab
