#include <fmt/format.h>

#include "commands.hpp"
#include "memory_limit_option.hpp"
#include "scatterlab/io/simulation_file.hpp"

namespace scatterlab::cli {

Action add_info_command(CLI::App& app) {
  auto* info = app.add_subcommand("info", "Summarise a scatterlab HDF5 file");
  auto path = std::make_shared<std::string>();
  info->add_option("FILE", *path, "File written by scatterlab")->required();
  add_memory_limit_option(*info);
  return [path] {
    fmt::print("{}", describe_simulation_file(*path));
    return 0;
  };
}

}  // namespace scatterlab::cli
