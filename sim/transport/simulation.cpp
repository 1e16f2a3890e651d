#include "scatterlab/transport/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

#include "scatterlab/core/error.hpp"
#include "scatterlab/transport/grid_checks.hpp"
#include "scatterlab/transport/length_units.hpp"

namespace scatterlab {
namespace {

// Field names below are those the user writes: the TOML keys of the scene file, which the CLI
// options mirror (docs/architecture.md, "Errors").

// 2^28 doubles are 2 GiB for the mean alone; batch accumulators and per-order siblings multiply
// that, so a larger radiance array is a mistake rather than a wish.
constexpr std::uint64_t max_radiance_cells = std::uint64_t{1} << 28;
constexpr double two_pi = 2.0 * std::numbers::pi;

// Axis ends that are fixed by geometry (0, pi, 2 pi) are compared with a little slack so that a
// value computed as 2 * pi elsewhere is not rejected over the last bit.
bool same_angle(double a, double b) {
  return std::abs(a - b) <= 1e-12;
}

std::string got(double value) {
  return fmt::format("got {}", value);
}

void check_medium(const Medium& medium) {
  medium.validate();
  check_length_unit(medium);
}

// Axes that start at 0 by construction: r (distance from the beam axis) and rho (distance from
// the point source).
void check_radial_axis(const UniformAxis& axis, const std::string& name) {
  check_from_zero(axis, name, "a distance from the source", "medium.length_unit");
}

void check_angle_axis(const UniformAxis& axis, const std::string& name, double max,
                      const std::string& accepted_max) {
  if (!same_angle(axis.min, 0.0)) {
    throw InputError("grid." + name + ".min", got(axis.min), "0");
  }
  if (!same_angle(axis.max, max)) {
    throw InputError("grid." + name + ".max", got(axis.max), accepted_max);
  }
  check_bins(axis, name);
}

void check_grid(const Grid& grid, bool radiance_requested, const Medium& medium) {
  check_radial_axis(grid.r, "r");

  if (!std::isfinite(grid.z.min)) {
    throw InputError("grid.z.min", got(grid.z.min), "a finite number (in medium.length_unit)");
  }
  if (!(grid.z.max > grid.z.min) || !std::isfinite(grid.z.max)) {
    throw InputError("grid.z.max",
                     fmt::format("got {} with grid.z.min = {}", grid.z.max, grid.z.min),
                     "a finite number > grid.z.min (in medium.length_unit)");
  }
  check_bins(grid.z, "z");
  check_length_axis_span(grid.r, "r", medium);
  check_length_axis_span(grid.z, "z", medium);

  check_angle_axis(grid.theta, "theta", std::numbers::pi, "pi (theta spans [0, pi])");
  if (grid.fold_phi) {
    check_angle_axis(grid.phi, "phi", std::numbers::pi, "pi when grid.fold_phi = true");
  } else {
    check_angle_axis(grid.phi, "phi", two_pi, "2 pi when grid.fold_phi = false");
    // The bins of phi and 2 pi - phi mirror each other only for an even count (scorer.hpp).
    if (grid.phi.bins % 2 != 0) {
      throw InputError("grid.phi.bins",
                       fmt::format("got {} with grid.fold_phi = false", grid.phi.bins),
                       "an even number of bins over [0, 2 pi], or grid.fold_phi = true");
    }
  }
  check_radial_axis(grid.rho, "rho");
  check_length_axis_span(grid.rho, "rho", medium);

  if (radiance_requested) {
    // Each factor is at most 1e5 after check_bins, so the product fits in 64 bits.
    const auto cells =
        static_cast<std::uint64_t>(grid.r.bins) * static_cast<std::uint64_t>(grid.z.bins) *
        static_cast<std::uint64_t>(grid.theta.bins) * static_cast<std::uint64_t>(grid.phi.bins);
    if (cells > max_radiance_cells) {
      throw InputError("grid",
                       fmt::format("the radiance tally would have {} x {} x {} x {} = {} cells "
                                   "(r x z x theta x phi bins)",
                                   grid.r.bins, grid.z.bins, grid.theta.bins, grid.phi.bins, cells),
                       "at most 268435456 (2^28) cells: use fewer bins, or set "
                       "tallies.radiance = false");
    }
  }
}

void check_tallies(const TallyRequest& tallies, SourceKind source, bool declares) {
  if (tallies.estimator != Estimator::collision && tallies.estimator != Estimator::track_length) {
    throw InputError("tallies.estimator",
                     fmt::format("got code {}", static_cast<int>(tallies.estimator)),
                     "\"collision\" or \"track_length\"");
  }
  if (tallies.fluence_spherical && source != SourceKind::point) {
    throw InputError(
        "tallies.fluence_spherical",
        "requested with the " + to_string(source) + " source, which has no spherical symmetry",
        "true only with source.type = \"point\"");
  }
  if (!(tallies.radiance || tallies.fluence || tallies.flux || tallies.fluence_spherical ||
        declares)) {
    throw InputError("tallies", "no tally requested",
                     "at least one of radiance, fluence, flux, fluence_spherical = true, or a "
                     "[[tally]]");
  }
}

void check_run(const RunSettings& run, const Medium& medium) {
  check_run_settings(run);
  check_escape_radius_span(run.escape_radius, medium);
  if (medium.albedo == 1.0 && !std::isfinite(run.escape_radius)) {
    throw InputError("run.escape_radius",
                     "is infinite, but an infinite medium with albedo 1 never absorbs, so photons "
                     "never end; set run.escape_radius",
                     "a finite number > 0 (mfp) when medium.albedo = 1");
  }
  check_run_length(run, medium.albedo, run.escape_radius * mfp_per_length_unit(medium));
}

}  // namespace

void InfiniteMediumSpec::validate() const {
  check_medium(medium);
  if (source != SourceKind::pencil_beam && source != SourceKind::point) {
    throw InputError("source.type", fmt::format("got code {}", static_cast<int>(source)),
                     "\"beam\" or \"point\"");
  }
  check_grid(grid, tallies.radiance, medium);
  check_tallies(tallies, source, !declared_tallies.empty());
  check_run(run, medium);
  check_declared_tallies(declared_tallies, homogeneous_frame("infinite", medium, std::nullopt));
  if (!declared_tallies.empty() && tallies.estimator == Estimator::track_length) {
    throw InputError("tallies.estimator", "is \"track_length\" with [[tally]]",
                     "\"collision\": declared tallies are scored at collisions");
  }
}

std::string fingerprint(const InfiniteMediumSpec& spec) {
  // Doubles in hexadecimal ({:a}) so that the text, and so the hash, is exact.
  auto axis = [](const UniformAxis& a) {
    return fmt::format("{:a},{:a},{};", a.min, a.max, a.bins);
  };
  const Medium& m = spec.medium;
  const TallyRequest& t = spec.tallies;
  const RunSettings& run = spec.run;
  const std::string canonical = fmt::format(
      "medium {:a} {:a} {:a} {}|source {}|grid {}{}{}{}{}{}|tallies {}{}{}{}{} {}|run {} {} {} "
      "{:a}",
      m.albedo, m.g, m.sigma_t, m.length_unit, to_string(spec.source), axis(spec.grid.r),
      axis(spec.grid.z), axis(spec.grid.theta), axis(spec.grid.phi), axis(spec.grid.rho),
      spec.grid.fold_phi, t.radiance, t.fluence, t.flux, t.fluence_spherical, t.split_by_order,
      to_string(t.estimator), run.photons, run.batches, run.seed, run.escape_radius);
  return fingerprint_of(canonical + fingerprint_text(spec.declared_tallies));
}

std::string to_string(SourceKind source) {
  switch (source) {
    case SourceKind::pencil_beam:
      return "beam";
    case SourceKind::point:
      return "point";
  }
  return "unknown";
}

std::string to_string(Estimator estimator) {
  switch (estimator) {
    case Estimator::none:
      return "none";
    case Estimator::collision:
      return "collision";
    case Estimator::track_length:
      return "track_length";
  }
  return "unknown";
}

}  // namespace scatterlab
