#include "memory_limit_option.hpp"

#include <string>

#include "scatterlab/core/error.hpp"
#include "scatterlab/core/memory_budget.hpp"

namespace scatterlab::cli {

void add_memory_limit_option(CLI::App& command) {
  // A bad size is a parse error (one line naming the flag, status 2, before any work); a good one
  // sets the process's limit as the command line is read, the last one given winning.
  const CLI::Validator size(
      [](std::string& text) {
        try {
          parse_memory_size(text, "--memory-limit");
          return std::string();
        } catch (const InputError& e) {
          return std::string(e.what()).substr(e.field().size() + 2);  // CLI11 names the flag
        }
      },
      "");
  command
      .add_option_function<std::string>(
          "--memory-limit",
          [](const std::string& text) {
            set_memory_limit(parse_memory_size(text, "--memory-limit"), text);
          },
          "Memory the run may use, e.g. 512M or 4G (K, M, G, T: powers of 1024); by default the "
          "machine's physical memory, or its cgroup's limit, or what ulimit -v leaves, "
          "whichever is lowest. The run's peak "
          "(tallies, a buffer per thread, images, datasets read) is estimated before anything "
          "is allocated, and a run over the limit is refused, naming the fields that size it")
      ->type_name("SIZE")
      ->default_str(format_bytes(machine_memory_limit().bytes))
      ->check(size);
}

}  // namespace scatterlab::cli
