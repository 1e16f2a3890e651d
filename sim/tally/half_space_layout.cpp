#include "scatterlab/tally/half_space_layout.hpp"

#include <cmath>
#include <string>

#include "scatterlab/core/constants.hpp"

namespace scatterlab {
namespace {

std::size_t count(const UniformAxis& axis) {
  return static_cast<std::size_t>(axis.bins);
}

// Area of the ring r0 <= r < r1 of surface, in mfp^2.
double ring_area(const UniformAxis& r, std::size_t ir) {
  const double r0 = r.edge(static_cast<int>(ir)), r1 = r.edge(static_cast<int>(ir) + 1);
  return pi * (r1 * r1 - r0 * r0);
}

// Projected solid angle of the exit cone band theta0 <= theta_o < theta1, all azimuths:
// integral of cos theta dw = pi (sin^2 theta1 - sin^2 theta0), in sr.
double projected_solid_angle(const UniformAxis& theta, std::size_t itheta) {
  const double s0 = std::sin(theta.edge(static_cast<int>(itheta)));
  const double s1 = std::sin(theta.edge(static_cast<int>(itheta) + 1));
  return pi * (s1 * s1 - s0 * s0);
}

const char* order_suffix(std::size_t block) {
  static const char* suffixes[] = {"", "_unscattered", "_single", "_multiple"};
  return suffixes[block];
}

const char* order_words(std::size_t block) {
  // Unscattered light only travels deeper: it never leaves a half-space, so the unscattered
  // surface tallies are zero by construction; they are written so that every order sums.
  static const char* words[] = {"", " (unscattered light only)", " (light scattered exactly once)",
                                " (light scattered twice or more)"};
  return words[block];
}

}  // namespace

HalfSpaceLayout::HalfSpaceLayout(const SearchlightSpec& spec) {
  r_bins = count(spec.grid.r);
  z_bins = count(spec.grid.z);
  theta_bins = count(spec.grid.theta_o);
  std::size_t next = 0;
  reflectance = next;
  next += r_bins;
  radiance = next;
  next += r_bins * theta_bins;
  if (spec.tallies.fluence) {
    fluence = next;
    next += r_bins * z_bins;
  }
  diffuse = next++;
  block_size = next;
  absorbed = blocks * block_size;
  escaped = absorbed + 1;
  size = escaped + 1;
}

std::vector<TallyResult> finalize_half_space_tallies(const SearchlightSpec& spec,
                                                     const HalfSpaceLayout& layout,
                                                     const EntryPower& entry,
                                                     const std::vector<double>& raw_mean,
                                                     const std::vector<double>& raw_stderr) {
  const SearchlightGrid& grid = spec.grid;
  std::vector<TallyResult> results;

  // Copies the raw counts from `offset`, scaling cell i by (power entering) / measure(i).
  auto add = [&](std::string name, std::vector<std::string> dims, std::vector<std::size_t> shape,
                 std::string units, std::string description, std::size_t offset, auto&& measure) {
    TallyResult t = measured_tally({std::move(name),
                                    std::move(dims),
                                    std::move(shape),
                                    std::move(units),
                                    std::move(description),
                                    {},
                                    {}},
                                   raw_mean, raw_stderr, offset, measure);
    for (double& v : t.mean) v *= entry.transmitted;
    for (double& v : t.stderr_of_mean) v *= entry.transmitted;
    results.push_back(std::move(t));
  };
  auto unit = [](std::size_t) { return 1.0; };

  for (std::size_t block = 0; block < HalfSpaceLayout::blocks; ++block) {
    const std::size_t base = block * layout.block_size;
    const std::string suffix = order_suffix(block);
    const std::string scope = order_words(block);
    add("reflectance" + suffix, {"r"}, {layout.r_bins}, "W mfp^-2 per W incident",
        "diffuse reflectance R_d(r): power leaving the surface per unit area, ring average" + scope,
        base + layout.reflectance, [&](std::size_t i) { return ring_area(grid.r, i); });
    add("exitant_radiance" + suffix, {"r", "theta_o"}, {layout.r_bins, layout.theta_bins},
        "W mfp^-2 sr^-1 per W incident",
        "radiance leaving the surface outside the medium, L(r, theta_o) with theta_o from the "
        "outward normal: power / (ring area x projected solid angle) of the bin" +
            scope,
        base + layout.radiance, [&](std::size_t i) {
          return ring_area(grid.r, i / layout.theta_bins) *
                 projected_solid_angle(grid.theta_o, i % layout.theta_bins);
        });
    if (layout.fluence != HalfSpaceLayout::absent) {
      add("fluence" + suffix, {"r", "z"}, {layout.r_bins, layout.z_bins}, "W mfp^-2 per W incident",
          "fluence phi(r, z) inside the medium, bin average, collision estimator" + scope,
          base + layout.fluence,
          [&](std::size_t i) { return ring_area(grid.r, i / layout.z_bins) * grid.z.width(); });
    }
    add("diffuse_reflectance" + suffix, {}, {}, "W per W incident",
        "total power leaving the surface after scattering (all radii and angles)" + scope,
        base + layout.diffuse, unit);
  }

  TallyResult specular{"specular_reflectance",
                       {},
                       {},
                       "W per W incident",
                       "Fresnel reflection of the beam at entry (exact: no standard error)",
                       {entry.specular},
                       {0.0}};
  results.push_back(std::move(specular));
  add("absorbed", {}, {}, "W per W incident", "power absorbed anywhere in the medium",
      layout.absorbed, unit);
  if (std::isfinite(spec.run.escape_radius)) {
    add("escaped", {}, {}, "W per W incident",
        "power carried past the escape radius (see /parameters escape_radius)", layout.escaped,
        unit);
  }
  return results;
}

}  // namespace scatterlab
