#include "run_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scatterlab/tally/figure_of_merit.hpp"
#include "scatterlab/tally/scalar_estimate.hpp"

namespace scatterlab::cli {

void print_run_time(const TransportOutput& out) {
  const double events = static_cast<double>(out.scattering_events);
  const double seconds = out.run_wall_seconds();
  const std::string ranks = out.ranks > 1 ? fmt::format("{} ranks x ", out.ranks) : "";
  // Per event, the walk's time only: set-up, the batches' tallies and finishing do not grow with
  // the events, and in a small run they would read as a slow walk.
  fmt::print(
      "  {} photons in {} batches on {}{} thread{}: {:.2f} s ({:.3g} photons/s, {:.3g} "
      "scattering events, {:.1f} ns per event per thread in the walk; {:.2f} s outside it)\n",
      out.photons, out.batches_done, ranks, out.threads, out.threads == 1 ? "" : "s", seconds,
      static_cast<double>(out.photons) / seconds, events,
      out.walk_events > 0 ? out.walk_seconds / static_cast<double>(out.walk_events) * 1e9 : 0.0,
      std::max(0.0, out.wall_seconds - out.walk_seconds / out.threads));
  if (out.threads < out.threads_asked) {
    fmt::print("  OpenMP granted {} of the {} threads asked for (OMP_DYNAMIC, OMP_THREAD_LIMIT)\n",
               out.threads, out.threads_asked);
  }
  if (out.photons_resumed == 0) return;
  fmt::print(
      "  this session: {} photons in {:.2f} s ({:.3g} photons/s), after {} photons in {:.2f} s "
      "before --resume\n",
      out.session_photons(), out.wall_seconds,
      static_cast<double>(out.session_photons()) / out.wall_seconds, out.photons_resumed,
      out.resumed_wall_seconds);
}

void print_energy_balance(const TransportOutput& out, const std::vector<std::string>& names) {
  std::string energy = "  energy per W incident:";
  double total = 0.0;
  for (const std::string& name : names) {
    if (find_tally(out.tallies, name) == nullptr) continue;
    const ScalarEstimate value = scalar_estimate(out.tallies, name);
    energy += fmt::format(" {} {},", name, estimate_text(value));
    total += value.mean;
  }
  fmt::print("{} total {:.6f}\n", energy, total);
}

void print_figures_of_merit(const TransportOutput& out, const std::vector<std::string>& names) {
  std::string figures;
  for (const std::string& name : names) {
    const TallyResult* tally = find_tally(out.tallies, name);
    if (tally == nullptr) continue;
    const double merit = figure_of_merit(
        relative_standard_error(tally->mean, tally->stderr_of_mean), out.run_wall_seconds());
    if (!std::isfinite(merit)) continue;
    figures += fmt::format("{} {} {:.3g}{}", figures.empty() ? "" : ",", name, merit,
                           tally->shape.empty() ? "" : " (median bin)");
  }
  if (!figures.empty()) fmt::print("  figure of merit 1/(R^2 T), 1/s:{}\n", figures);
}

}  // namespace scatterlab::cli
