// scatterlab: Monte Carlo transport of light in participating media, from the command line. The
// core program: the commands that run photons and read their files; the commands of fit and
// explore run in those components' programs (program.hpp).
#include <cstdio>
#include <exception>
#include <vector>

#include "commands.hpp"
#include "component_program.hpp"
#include "program.hpp"

namespace {

using scatterlab::cli::Command;

std::vector<Command> core_commands(CLI::App& app, const std::string& command_line,
                                   scatterlab::World& world) {
  using namespace scatterlab::cli;
  std::vector<Command> commands;
  commands.push_back({"simulate", add_simulate_command(app, command_line, world)});
  commands.push_back({"searchlight", add_searchlight_command(app, command_line, world)});
  commands.push_back({"scene", add_scene_command(app)});
  commands.push_back({"materials", add_materials_command(app)});
  commands.push_back({"info", add_info_command(app)});
  commands.push_back({"validate", add_validate_command(app)});
  commands.push_back({"merge", add_merge_command(app, command_line)});
#ifdef SCATTERLAB_WITH_FIT
  list_component_command(app, "fit", kFitDescription);
  list_component_command(app, "report", kReportDescription);
#else
  const char* ceres = "Ceres (Debian: libceres-dev)";
  commands.push_back({"fit", add_unavailable_command(app, "fit", "Lobe fits", ceres)});
  commands.push_back(
      {"report", add_unavailable_command(app, "report", "The accuracy report", ceres)});
#endif
#ifdef SCATTERLAB_WITH_RENDER
  commands.push_back({"render", add_render_command(app)});
#else
  commands.push_back(
      {"render", add_unavailable_command(app, "render", "Images of objects",
                                         "Embree, tinyobjloader, OpenEXR and libpng (Debian: "
                                         "libembree-dev, libtinyobjloader-dev, libopenexr-dev, "
                                         "libpng-dev)")});
#endif
  commands.push_back({"invert", add_invert_command(app)});
#ifdef SCATTERLAB_WITH_EXPLORE
  list_component_command(app, "explore", kExploreDescription);
#else
  commands.push_back({"explore", add_unavailable_command(
                                     app, "explore", "The explorer in a browser",
                                     "cpp-httplib, nlohmann-json and muparser (Debian: "
                                     "libcpp-httplib-dev, nlohmann-json3-dev, libmuparser-dev)")});
#endif
  commands.push_back({"mcml", add_mcml_command(app, command_line, world)});
  return commands;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) {
    try {
      scatterlab::cli::run_component_program(argv);  // returns when argv[1] is a core command
    } catch (const std::exception& e) {
      std::fprintf(stderr, "scatterlab: failed: %s\n", e.what());
      return 1;
    }
  }
  return scatterlab::cli::run_program(argc, argv, core_commands);
}
