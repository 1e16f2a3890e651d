#pragma once
// The one step every writing command takes before any work: its OutputPlan is checked (an
// InputError naming the flag when an output would destroy an input or another output, or names
// something that is not a file), and the temporaries a killed run left beside its outputs are
// removed and reported. The output directories are made later, by plan.make_output_directories(),
// once every input has been read and checked: bad input leaves no directory behind.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <string>

#include "long_run.hpp"
#include "scatterlab/io/output_plan.hpp"

namespace scatterlab::cli {

// `root`: whether this process is the one that writes and prints (MPI rank 0, or the only one).
void prepare_outputs(const OutputPlan& plan, bool root = true);

// The outputs of a command that runs one scene into one file (searchlight, the lit sphere, the
// slab): the file is --out when given, else the scene's [output] path, else `default_name`; it,
// its checkpoint and the scene (when one was given) are planned and prepared. Returns the file.
std::filesystem::path prepare_scene_outputs(const CLI::App& command, const std::string& scene,
                                            const std::string& out,
                                            const std::optional<std::string>& scene_output,
                                            const std::string& default_name,
                                            const LongRunOptions& long_run, bool root);

}  // namespace scatterlab::cli
