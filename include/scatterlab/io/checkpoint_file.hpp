#pragma once
// Checkpoints: the state of a run after a whole number of batches (run_control.hpp), written
// beside the output so that a killed run can continue with --resume and end with the same file,
// bit for bit, as an uninterrupted one.
//
//   /   attrs format="scatterlab-checkpoint", format_version=2, spec_fingerprint, batches_folded,
//             scattering_events, wall_seconds (the run's wall time so far, over every process
//             that ran it), created, checksum (FNV-1a of the fingerprint, the three counts and
//             the bytes of both arrays, core/fnv1a.hpp: a resumed run trusts nothing edited)
//   /welford_mean, /welford_squares   1-D, one value per tally cell, per photon (raw, before
//                                     division by bin volume and solid angle)
//
// Written to a temporary name and renamed, so a kill during the write leaves the previous
// checkpoint intact.

#include <filesystem>
#include <string>

#include "scatterlab/transport/run_control.hpp"

namespace scatterlab {

// "<output>.checkpoint"
std::filesystem::path default_checkpoint_path(const std::filesystem::path& output);

void write_checkpoint(const std::filesystem::path& path, const std::string& spec_fingerprint,
                      const RunState& state);

// Whether `path` is a checkpoint written for this run (`spec_fingerprint`): the only kind of file
// a run may replace or remove at its checkpoint path. Never throws.
bool is_checkpoint_of(const std::filesystem::path& path, const std::string& spec_fingerprint);

// Throws InputError naming `field` (the option that pointed here) when the file is missing, not
// a checkpoint, was written for a run with another fingerprint (other parameters or seed), or
// holds anything that does not match its checksum.
RunState read_checkpoint(const std::filesystem::path& path, const std::string& spec_fingerprint,
                         const std::string& field = "--resume");

}  // namespace scatterlab
