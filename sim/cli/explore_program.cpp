// scatterlab-explore: the explorer's server (cpp-httplib), which `scatterlab explore` runs
// (program.hpp).
#include "commands.hpp"
#include "program.hpp"

int main(int argc, char** argv) {
  using namespace scatterlab::cli;
  return run_program(argc, argv, [](CLI::App& app, const std::string&, scatterlab::World&) {
    return std::vector<Command>{{"explore", add_explore_command(app)}};
  });
}
