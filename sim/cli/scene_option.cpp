#include "scene_option.hpp"

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/text_file.hpp"

namespace scatterlab::cli {

CLI::Validator scene_file() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        try {
          check_scene_file(path, "");
          return "";
        } catch (const InputError& e) {
          // CLI11 puts the flag's name in front; the field given here is empty.
          return std::string(e.what()).substr(2);
        }
      },
      "FILE");
}

CLI::Option* add_scene_option(CLI::App& command, std::string& scene, const std::string& example) {
  return command
      .add_option("SCENE,--scene", scene,
                  "TOML scene file, a regular file of at most 1 MiB (see " + example +
                      "); flags given beside it override its values")
      ->check(scene_file())
      // One scene: two (a positional file and --scene) would be a silent choice of one.
      ->multi_option_policy(CLI::MultiOptionPolicy::Throw);
}

}  // namespace scatterlab::cli
