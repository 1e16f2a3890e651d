#pragma once
// The scene file, named the same way by every command that reads one: `--scene FILE` or the file
// as a positional argument (`scatterlab simulate run.toml`).

#include <CLI/CLI.hpp>
#include <string>

namespace scatterlab::cli {

// A regular file of at most 1 MiB (io/text_file.hpp), checked before it is opened.
CLI::Validator scene_file();

// Registers SCENE / --scene into `scene`; `example` is a shipped scene the help points to.
CLI::Option* add_scene_option(CLI::App& command, std::string& scene, const std::string& example);

}  // namespace scatterlab::cli
