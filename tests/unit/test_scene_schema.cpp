// The scene's one table of keys (io/scene_schema.hpp) against the reader that reads them: every
// key the schema lists for a geometry is read by that geometry's reader (a value of the wrong
// type is refused naming the key), so that no key the schema accepts is silently ignored; and
// the reader refuses a key the schema does not list for the geometry.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scatterlab/core/error.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/io/scene_schema.hpp"
#include "scatterlab/render/render_scene.hpp"

namespace scatterlab {
namespace {

// The smallest scene of each geometry that reads, as dotted keys (a layer's and a declared
// tally's in their inline tables), with the key at `path` ("grid.r.max"; "layers.g", the first
// layer's; "tally.filters.t.max") set to `value`, a TOML value as text.
std::string scene_with(std::string_view geometry, std::string_view path, std::string_view value) {
  using Keys = std::vector<std::pair<std::string, std::string>>;
  Keys root = {{"geometry.type", fmt::format("\"{}\"", geometry)}};
  Keys layer;
  if (geometry == "mesh") {
    // A shape that takes the key (render_scene.cpp): another shape refuses it by name anyway.
    std::string_view shape = "sphere";
    if (path == "mesh.amplitude" || path == "mesh.frequency") shape = "bumpy_sphere";
    if (path == "mesh.exponent" || path == "mesh.half_size") shape = "rounded_tile";
    if (path == "mesh.path") shape = "obj";
    root.emplace_back("mesh.shape", fmt::format("\"{}\"", shape));
  }
  if (geometry == "slab")
    layer = {{"mu_a", "1.0"}, {"mu_s", "10.0"}, {"g", "0.9"}, {"n", "1.4"}, {"thickness", "1.0"}};
  // A declared tally's keys in the one [[tally]] of the smallest declaration.
  Keys tally;
  const bool in_tally = path.starts_with("tally.");
  if (in_tally) tally = {{"name", "\"t\""}, {"score", "\"absorbed\""}};
  const bool in_layer = path.starts_with("layers.");
  Keys& keys = in_layer ? layer : in_tally ? tally : root;
  const std::string key(in_layer ? path.substr(7) : in_tally ? path.substr(6) : path);
  const auto it =
      std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.first == key; });
  if (it != keys.end()) {
    it->second = value;
  } else {
    keys.emplace_back(key, value);
  }
  std::string text;
  for (const auto& [name, text_value] : root) text += fmt::format("{} = {}\n", name, text_value);
  if (!layer.empty()) {
    std::string entries;
    for (const auto& [name, text_value] : layer) {
      entries += fmt::format("{}{} = {}", entries.empty() ? "" : ", ", name, text_value);
    }
    text += fmt::format("layers = [{{{}}}]\n", entries);
  }
  if (!tally.empty()) {
    std::string entries;
    for (const auto& [name, text_value] : tally) {
      entries += fmt::format("{}{} = {}", entries.empty() ? "" : ", ", name, text_value);
    }
    text += fmt::format("tally = [{{{}}}]\n", entries);
  }
  return text;
}

// The field of the error that reading `text` as a scene (and its mesh) raises; "" for none.
std::string refusal_of(const std::string& text) {
  try {
    const Scene scene = parse_scene(text, "schema.toml", Validation::by_caller);
    if (scene.mesh_text) parse_scene_mesh(*scene.mesh_text, "schema.toml");
  } catch (const InputError& error) {
    return error.field();
  }
  return "";
}

TEST(SceneSchema, TheReaderReadsEveryKeyItLists) {
  int checked = 0;
  for (const SceneKey& key : scene_keys()) {
    for (const std::string_view geometry : scene_geometries) {
      if (!scene_key_of(key, geometry)) continue;
      // A value of another type: a string where the key takes anything else, else a number.
      const std::string text =
          scene_with(geometry, key.path, key.value == SceneValue::string ? "12345" : "\"wrong\"");
      const std::string field = refusal_of(text);
      // The field names the key: "layers[1].g" for "layers.g".
      const std::string_view path = key.path;
      const std::string_view table = path.substr(0, path.find('.'));
      const std::string_view name = path.substr(path.rfind('.') + 1);
      EXPECT_TRUE(field.starts_with(table) && field.ends_with(name))
          << geometry << " " << key.path << ": refused as \"" << field << "\"\n"
          << text;
      ++checked;
    }
  }
  EXPECT_GT(checked, 140);
}

TEST(SceneSchema, TheReaderRefusesAKeyTheSchemaDoesNotListForTheGeometry) {
  for (const SceneKey& key : scene_keys()) {
    for (const std::string_view geometry : scene_geometries) {
      if (scene_key_of(key, geometry)) continue;
      // Another geometry's key, in a table this geometry has or not: refused by its name.
      const std::string text =
          scene_with(geometry, key.path, key.value == SceneValue::string ? "\"x\"" : "1.0");
      const std::string field = refusal_of(text);
      EXPECT_FALSE(field.empty()) << geometry << " accepts " << key.path << "\n" << text;
    }
  }
}

}  // namespace
}  // namespace scatterlab
