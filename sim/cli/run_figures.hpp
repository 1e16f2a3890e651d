#pragma once
// The lines of a transport run's summary that say what the run cost: its time and rates over the
// whole run (every process that ran it, --resume included) and this process's share, and the
// figures of merit of its main tallies (tally/figure_of_merit.hpp). Shared by simulate and
// searchlight, so that both print the same figures the file keeps.

#include <cstdint>
#include <string>
#include <vector>

#include "scatterlab/transport/engine.hpp"

namespace scatterlab::cli {

// The slab's totals, as its summaries print them (simulate, mcml): with analog absorption every
// photon ends in exactly one of them.
inline const std::vector<std::string> slab_energy_tallies = {
    "specular_reflectance", "diffuse_reflectance", "total_transmittance", "absorbed"};

// "  N photons in B batches on T threads: S s (R photons/s, ...)" over the whole run; after a
// --resume also "  this session: ..." with this process's own figures.
void print_run_time(const TransportOutput& out);

// "  energy per W incident: absorbed 0.5 ± 0.001, escaped 0.5 ± 0.001, total 1.000000": the
// scalar totals among `names` that the run has, each as estimate_text prints it, and their sum,
// which is 1 where every photon ends in exactly one of them.
void print_energy_balance(const TransportOutput& out, const std::vector<std::string>& names);

// "  figure of merit 1/(R^2 T), 1/s: absorbed 3.1e+05, fluence 1.2e+03 (median bin), ..." for
// those of `names` the run has and whose figure is defined, T the whole run's wall time.
void print_figures_of_merit(const TransportOutput& out, const std::vector<std::string>& names);

}  // namespace scatterlab::cli
