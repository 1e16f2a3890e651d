#pragma once
// Scene files: a TOML description of one simulation, read strictly into a validated
// SimulationSpec (docs/architecture.md, "From a scene to a file"). Anything the file leaves out
// keeps the default of SimulationSpec, which is the paper's case (Vavassori §4.1);
// data/scenes/paper-beam.toml spells every key out with its meaning and units.
//
//   [geometry] type = "infinite"              (the default; the half-space is below)
//   [medium]   albedo, sigma_t, g            (length_unit defaults to "mfp")
//          or  sigma_a, sigma_s, g           (length_unit defaults to "mm")
//          or  material = "apple", channel = "red", optionally g and length_unit: a measured
//              material from data/materials (io/material_presets.hpp, resolve_material)
//              length_unit = "mfp" | "um" | "mm" | "cm" | "m"
//   [source]   type = "beam" | "point"
//   [grid]     r = { max, bins }, z = { min, max, bins }, theta = { bins }, phi = { bins },
//              fold_phi = bool, rho = { max, bins }        (lengths in medium.length_unit)
//   [tallies]  radiance, fluence, flux, fluence_spherical, split_by_order = bool,
//              estimator = "collision" | "track_length"
//   [run]      photons, batches, seed, threads (integers; 1e7-style floats that are whole numbers
//              are accepted too), escape_radius (number in medium.length_unit, or inf)
//   [output]   path = "file.h5"
//
// For the point source, tallies.fluence_spherical defaults to true (its natural tally, the
// d'Eon & Irving 2011 curves) unless the file sets it; for the beam it stays false.
//
// Strict: an unknown table or key, a wrong type, or a value out of range is an InputError
// naming the dotted key (e.g. "medium.albdo") and what is accepted; a TOML syntax error is an
// InputError for "scene" whose message starts "<origin>:<line>:<column>:".

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/lit_sphere.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

// Whether reading also validates the spec. Reading is strict either way: an unknown key, a wrong
// type or a malformed value is refused as read. on_read then validates the whole spec; by_caller
// leaves that to code that lays more over it first, as the command line does with its flags, so
// that a flag can mend a scene (photons = 10 with --batches 4) and every refusal names the value
// that is in force.
enum class Validation { on_read, by_caller };

struct Scene {
  SimulationSpec spec;                      // validated unless read with Validation::by_caller
  std::optional<std::string> output_path;   // [output] path, as written; the CLI resolves it
  std::optional<MaterialRequest> material;  // [medium] material and its keys, as written
};

// `origin` names the text in messages (usually its file name).
Scene parse_scene(std::string_view toml_text, const std::string& origin,
                  Validation validation = Validation::on_read);

// Reads and parses a file; an unreadable file is an InputError for "scene".
Scene load_scene(const std::filesystem::path& path, Validation validation = Validation::on_read);

// Parameter sweeps: in a sweep file any scalar key may hold a list of values instead of one,
//   [medium]
//   albedo = [0.5, 0.9]
//   g = [0, 0.9]
// and the file stands for every combination (here four scenes), each read and validated as a
// scene. Combinations are ordered as the lists appear in the file, the last varying fastest.
struct SweepPoint {
  // The swept keys and values, e.g. "albedo=0.5_g=0.9": names the point's output file. Keys
  // are the last part of the dotted key unless two swept keys share it ("r.max=2_rho.max=10").
  // Empty for a file without lists.
  std::string label;
  Scene scene;
};

// A sweep is one run and one output file per point, all planned (and every memory estimate
// checked) before the first run starts, and a directory of a thousand files is already more than
// one study reads. Past this many, a study is split into several sweep files. The count is taken
// from the lengths of the lists before any point is made.
inline constexpr std::uint64_t max_sweep_points = 1'000;

// Throws InputError naming the swept keys when their lists make more than max_sweep_points.
std::vector<SweepPoint> parse_sweep(std::string_view toml_text, const std::string& origin,
                                    Validation validation = Validation::on_read);
std::vector<SweepPoint> load_sweep(const std::filesystem::path& path,
                                   Validation validation = Validation::on_read);

// The searchlight's scene (scatterlab searchlight --scene; data/scenes/searchlight.toml), as
// strict as the above, with these tables:
//   [geometry] type = "half_space", eta = n_medium / n_outside
//   [medium]   as above: albedo, g (mfp); albedo, sigma_t, g, length_unit; sigma_a, sigma_s, g;
//              or material, channel (g, length_unit): the material's eta too, unless given
//   [surface]  eta                                         (the same eta, as older files say)
//   [source]   incidence_deg
//   [grid]     r = { max, bins }, z = { max, bins }, theta_o = { bins },
//              x = { min, max, bins }, y = { min, max, bins }   (the exitance map's cells)
//   [tallies]  fluence = bool, exitance_map = bool
//   [run]      as above;  [output] path
struct SearchlightScene {
  SearchlightSpec spec;                     // validated unless read with Validation::by_caller
  std::optional<std::string> output_path;   // [output] path, as written
  std::optional<MaterialRequest> material;  // [medium] material and its keys, as written
  bool eta_given = false;                   // geometry.eta or surface.eta in the file
};

SearchlightScene parse_searchlight_scene(std::string_view toml_text, const std::string& origin,
                                         Validation validation = Validation::on_read);
SearchlightScene load_searchlight_scene(const std::filesystem::path& path,
                                        Validation validation = Validation::on_read);

// The lit sphere's scene (scatterlab simulate on a scene whose geometry.type is "sphere" or
// "mesh"; data/scenes/lit-sphere.toml, lit-mesh.toml), as strict as the above:
//   [geometry] type = "sphere", radius (in medium.length_unit), eta = n_medium / n_outside;
//              or type = "mesh" and eta, with a [mesh] table as a render scene's (no [grid])
//   [medium]   as above; a material brings its table's eta unless geometry.eta is given
//   [source]   type = "directional" | "pole_beam" | "beam" | "sphere"; for a beam, origin =
//              [x, y, z] (outside the sphere, in medium.length_unit) and direction = [x, y, z];
//              for a sphere of light (on a mesh), position = [x, y, z] and radius
//   [grid]     psi = { bins }       (the angle from the lit pole, over [0, pi]),
//              azimuth = { bins }   (about z from +x, over [0, 2 pi]; 1 by default)
//   [tallies]  split_by_order = bool
//   [run]      photons, batches, seed, threads;  [output] path
struct LitSphereScene {
  LitSphereSpec spec;                       // validated unless read with Validation::by_caller
  std::optional<std::string> output_path;   // [output] path, as written
  std::optional<MaterialRequest> material;  // [medium] material and its keys, as written
  bool eta_given = false;                   // geometry.eta in the file
  // geometry.type = "mesh": the object is the [mesh] table's (read as render reads it,
  // render/render_scene.hpp), which the caller puts in spec.mesh before validating.
  bool mesh = false;
};

LitSphereScene parse_lit_sphere_scene(std::string_view toml_text, const std::string& origin,
                                      Validation validation = Validation::on_read);
LitSphereScene load_lit_sphere_scene(const std::filesystem::path& path,
                                     Validation validation = Validation::on_read);

// The layered slab's scene (scatterlab simulate on a scene whose geometry.type is "slab";
// data/scenes/skin-slab.toml), as strict as the above:
//   [geometry]  type = "slab", length_unit (cm by default), n_above, n_below
//   [[layers]]  top down: mu_a, mu_s (1/length_unit), g, n, thickness (inf for a semi-infinite
//               last layer); or material, channel (g, n) and thickness
//   [grid]      r = { max, bins }, z = { max, bins }, theta_o = { bins }
//   [tallies]   split_by_order = bool
//   [run]       photons, batches, seed, threads, escape_radius, weighting = "analog" |
//               "implicit";  [output] path
struct LayeredSlabScene {
  LayeredSlabSpec spec;                    // validated unless read with Validation::by_caller
  std::optional<std::string> output_path;  // [output] path, as written
};

LayeredSlabScene parse_layered_slab_scene(std::string_view toml_text, const std::string& origin,
                                          Validation validation = Validation::on_read);
LayeredSlabScene load_layered_slab_scene(const std::filesystem::path& path,
                                         Validation validation = Validation::on_read);

// The scene's geometry.type ("infinite" when it gives none), for a command that runs more than
// one; the file's other errors are left to its reader.
std::string scene_geometry(const std::filesystem::path& path);

}  // namespace scatterlab
