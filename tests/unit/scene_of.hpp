#pragma once
// Tests of one geometry read a scene through the one reader (io/scene.hpp) and look at that
// geometry's spec: read_as<HalfSpaceSpec>(text, origin) reads a file that names no geometry as
// a half-space, and fails the test (std::bad_variant_access) when the file names another.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "scatterlab/io/scene.hpp"

namespace scatterlab::testing {

template <class Spec>
struct SceneOf {
  Spec spec;
  std::optional<std::string> output_path;
  std::optional<MaterialRequest> material;
  bool eta_given = false;
  bool mesh = false;
};

template <class Spec>
constexpr std::string_view geometry_of() {
  if constexpr (std::is_same_v<Spec, HalfSpaceSpec>) return "half_space";
  if constexpr (std::is_same_v<Spec, LitObjectSpec>) return "sphere";
  if constexpr (std::is_same_v<Spec, LayeredSlabSpec>) return "slab";
  return "infinite";
}

template <class Spec>
SceneOf<Spec> scene_of(Scene scene) {
  return {std::get<Spec>(std::move(scene.spec)), std::move(scene.output_path),
          std::move(scene.material), scene.eta_given, scene.mesh_text.has_value()};
}

template <class Spec>
SceneOf<Spec> read_as(std::string_view text, const std::string& origin,
                      Validation validation = Validation::on_read) {
  return scene_of<Spec>(parse_scene(text, origin, validation, geometry_of<Spec>()));
}

template <class Spec>
SceneOf<Spec> load_as(const std::filesystem::path& path,
                      Validation validation = Validation::on_read) {
  return scene_of<Spec>(load_scene(path, validation, geometry_of<Spec>()));
}

}  // namespace scatterlab::testing
