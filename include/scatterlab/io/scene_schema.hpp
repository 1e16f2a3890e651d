#pragma once
// The scene's keys, in one place: each key of every geometry's scene file (io/scene.hpp) with its
// type, what it accepts, its unit and its meaning. The reader checks every table's keys against
// it; `scatterlab scene --schema` writes a JSON Schema of scene files from it (for editors that
// check TOML as it is typed: Taplo, VS Code's Even Better TOML), `scatterlab scene --keys` the
// key reference (docs/scene-keys.md); the Python package reads its keyword-to-table map from it.
// The values' ranges are checked by each spec's validate(), which names the same dotted keys.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace scatterlab {

enum class SceneValue { number, integer, boolean, string, vector };

struct SceneKey {
  // Dotted from the top of the file: "medium.albedo", "grid.r.max"; a layer's key is
  // "layers.thickness" (every table of [[layers]]).
  std::string_view path;
  // The geometry.type values whose scenes take it, space-separated ("infinite half_space").
  std::string_view geometries;
  SceneValue value;
  // What is accepted, in words; for a string of fixed choices, the choices as TOML strings
  // ("\"beam\" \"point\"") and nothing else.
  std::string_view accepted;
  std::string_view meaning;  // with its unit
  bool choices = false;      // `accepted` lists the only strings accepted
};

// Every key, in the order the key reference lists them.
std::span<const SceneKey> scene_keys();

// Whether `key` (a SceneKey::path) is a key of `geometry`'s scenes.
bool scene_key_of(const SceneKey& key, std::string_view geometry);

// The names a table takes in `geometry`'s scenes, in schema order: for "" the top-level tables,
// for "grid" its keys and axes ("r", "fold_phi"), for "grid.r" the axis's keys.
std::vector<std::string_view> scene_table_keys(std::string_view geometry, std::string_view table);

// The JSON Schema (draft 2020-12) of scene files, sweeps included (any value may be a list of
// values), one branch per geometry.type.
std::string scene_json_schema();

// The key reference, as Markdown: a table per geometry.
std::string scene_key_reference();

}  // namespace scatterlab
