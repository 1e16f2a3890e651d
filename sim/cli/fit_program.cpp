// scatterlab-fit: the lobe fits and the accuracy report (Ceres), which `scatterlab fit` and
// `scatterlab report` run (program.hpp).
#include "commands.hpp"
#include "program.hpp"

int main(int argc, char** argv) {
  using namespace scatterlab::cli;
  return run_program(
      argc, argv, [](CLI::App& app, const std::string& command_line, scatterlab::World&) {
        return std::vector<Command>{{"fit", add_fit_command(app)},
                                    {"report", add_report_command(app, command_line)}};
      });
}
