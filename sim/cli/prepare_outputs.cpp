#include "prepare_outputs.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace scatterlab::cli {

void prepare_outputs(const OutputPlan& plan, bool root) {
  plan.check();
  if (!root) return;
  for (const auto& stale : plan.remove_stale_temporaries()) {
    fmt::print(stderr, "scatterlab: removed {}, left by a run killed while writing it\n",
               stale.string());
  }
}

std::filesystem::path prepare_scene_outputs(const CLI::App& command, const std::string& scene,
                                            const std::string& out,
                                            const std::optional<std::string>& scene_output,
                                            const std::string& default_name,
                                            const LongRunOptions& long_run, bool root) {
  const bool out_given = command.get_option("--out")->count() > 0;
  const std::filesystem::path output = out_given ? out : scene_output.value_or(default_name);
  OutputPlan plan;
  if (!scene.empty()) plan.input("--scene", scene);
  plan.output_file(out_given || !scene_output ? "--out" : "output.path", output);
  plan.output_file("--checkpoint", checkpoint_path(long_run, output));
  prepare_outputs(plan, root);
  return output;
}

}  // namespace scatterlab::cli
