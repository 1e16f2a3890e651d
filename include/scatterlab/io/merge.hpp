#pragma once
// Merging independent runs of the same scene (different seeds) into one file: their batches are
// pooled as one set (pooled_statistics.hpp), photons, scattering events and wall time add up.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace scatterlab {

struct MergeSummary {
  std::uint64_t photons = 0;
  std::uint64_t batches = 0;
  // True when the inputs hold different photons per batch: every batch still weighs the same in
  // the merged mean (unbiased, and so is its standard error), but not optimally.
  bool unequal_batches = false;
  // Why the inputs' /models were left out of the merged file (they differ); empty when every
  // input holds the same models (kept) or none.
  std::string models_dropped;
};

// Reads every input, checks that they agree in every parameter other than seed, photons, batches
// and threads, in the grid and in the tallies, and that no seed repeats; then writes `output`
// atomically. Mismatches are InputErrors naming the field ("parameters.albedo", "grid.r",
// "tallies.radiance", "parameters.seed") and both files. `command` is recorded as provenance,
// with the inputs.
//
// Every input must be complete (a partial file is refused: its run can still be finished with
// --resume, and then merged whole, once), of this format
// version, with batches_done, parameters.batches, photons_run and parameters.photons that agree,
// and with finite tallies (InputError "FILES" naming the file and what is wrong). /models is kept
// when every input holds the same models, and left out otherwise (see MergeSummary).
MergeSummary merge_simulation_files(const std::vector<std::filesystem::path>& inputs,
                                    const std::filesystem::path& output,
                                    const std::string& command);

}  // namespace scatterlab
