#pragma once
// Scene files: a TOML description of one simulation of any geometry, read once, strictly, into a
// Scene (docs/architecture.md, "From a scene to a file"). [geometry] type chooses the geometry
// once, as the file is read; each geometry's tables are below, and data/scenes/*.toml spell every
// key out with its meaning and units. Anything a file leaves out keeps its geometry's default
// spec (for the infinite medium, the paper's case, Vavassori §4.1).
//
// Strict: an unknown table or key, a wrong type, or a value out of range is an InputError
// naming the dotted key (e.g. "medium.albdo") and what is accepted; a TOML syntax error is an
// InputError for "scene" whose message starts "<origin>:<line>:<column>:".
//
// geometry.type = "infinite" (transport/simulation.hpp; data/scenes/paper-beam.toml):
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
// For the point source, tallies.fluence_spherical defaults to true (its natural tally, the
// d'Eon & Irving 2011 curves) unless the file sets it; for the beam it stays false.
//
// geometry.type = "half_space" (transport/searchlight.hpp; data/scenes/searchlight.toml):
//   [geometry] eta = n_medium / n_outside
//   [medium]   as above; a material brings its table's eta too, unless eta is given
//   [surface]  eta                                         (the same eta, as older files say)
//   [source]   incidence_deg
//   [grid]     r = { max, bins }, z = { max, bins }, theta_o = { bins },
//              x = { min, max, bins }, y = { min, max, bins }   (the exitance map's cells)
//   [tallies]  fluence = bool, exitance_map = bool
//   [run]      as above;  [output] path
//
// geometry.type = "sphere" or "mesh" (a lit object, transport/lit_object.hpp;
// data/scenes/lit-sphere.toml, lit-mesh.toml):
//   [geometry] radius (a sphere's, in medium.length_unit), eta = n_medium / n_outside
//   [mesh]     a mesh's object, as a render scene's [mesh] table (render/render_scene.hpp)
//   [medium]   as above; a material brings its table's eta unless geometry.eta is given
//   [source]   type = "directional" | "pole_beam" | "beam" | "sphere"; for a beam, origin =
//              [x, y, z] (outside the object, in medium.length_unit) and direction = [x, y, z];
//              for a sphere of light (on a mesh), position = [x, y, z] and radius
//   [grid]     psi = { bins }       (the angle from the lit pole, over [0, pi]),
//              azimuth = { bins }   (about z from +x, over [0, 2 pi]; 1 by default; a sphere's)
//   [tallies]  split_by_order = bool
//   [run]      photons, batches, seed, threads;  [output] path
//
// geometry.type = "slab" (transport/layered_slab.hpp; data/scenes/skin-slab.toml):
//   [geometry]  length_unit (cm by default), n_above, n_below
//   [[layers]]  top down: mu_a, mu_s (1/length_unit), g, n, thickness (inf for a semi-infinite
//               last layer); or material, channel (g, n) and thickness
//   [grid]      r = { max, bins }, z = { max, bins }, theta_o = { bins }
//   [tallies]   split_by_order = bool
//   [run]       photons, batches, seed, threads, escape_radius, weighting = "analog" |
//               "implicit";  [output] path

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "scatterlab/io/material_presets.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"
#include "scatterlab/transport/simulation.hpp"

namespace scatterlab {

// Whether reading also validates the spec. Reading is strict either way: an unknown key, a wrong
// type or a malformed value is refused as read. on_read then validates the whole spec; by_caller
// leaves that to code that lays more over it first, as the command line does with its flags, so
// that a flag can mend a scene (photons = 10 with --batches 4) and every refusal names the value
// that is in force. A mesh's spec is validated by the caller either way, once it holds the mesh.
enum class Validation { on_read, by_caller };

// One geometry's spec, the alternative geometry.type chose: the infinite medium, the half-space,
// a lit object (a sphere, or a mesh) or a layered slab.
using SceneSpec = std::variant<InfiniteMediumSpec, HalfSpaceSpec, LitObjectSpec, LayeredSlabSpec>;

// The geometry.type values ("sphere" and "mesh" are both a LitObjectSpec).
inline constexpr std::array<std::string_view, 5> scene_geometries = {"infinite", "half_space",
                                                                     "sphere", "mesh", "slab"};

struct Scene {
  SceneSpec spec;                           // validated unless read with Validation::by_caller
  std::optional<std::string> output_path;   // [output] path, as written; the caller resolves it
  std::optional<MaterialRequest> material;  // [medium] material and its keys, as written
  bool eta_given = false;                   // geometry.eta (or surface.eta) in the file
  // geometry.type = "mesh": a TOML text holding the scene's [mesh] table (the file's own text, or
  // a sweep point's written out), which the caller builds (it is render's:
  // render/render_scene.hpp, parse_scene_mesh) and puts in the spec's mesh before validating.
  std::optional<std::string> mesh_text;

  // The geometry.type this scene has: one of scene_geometries.
  std::string_view geometry() const;
};

// A scene's spec as the engine takes it, whatever its geometry: each geometry's
// transport_problem, fingerprint (what shapes its tallies: equal for a run and its resumption) and
// run. A mesh is traced with Embree in its own module, which runs it (mesh/lit_mesh.hpp,
// run_lit_mesh); run_spec refuses one with std::invalid_argument. Only the root rank gets tallies.
TransportProblem transport_problem(const SceneSpec& spec);
const RunSettings& run_settings(const SceneSpec& spec);
std::string fingerprint(const SceneSpec& spec);
TransportOutput run_spec(const SceneSpec& spec, const ProgressCallback& progress = {},
                         const RunControl& control = {});

// `origin` names the text in messages (usually its file name). `default_geometry` is the
// geometry of a file that names none (one of scene_geometries): "infinite" for simulate,
// "half_space" for searchlight.
Scene parse_scene(std::string_view toml_text, const std::string& origin,
                  Validation validation = Validation::on_read,
                  std::string_view default_geometry = "infinite");

// Reads and parses a file; an unreadable file is an InputError for "scene".
Scene load_scene(const std::filesystem::path& path, Validation validation = Validation::on_read,
                 std::string_view default_geometry = "infinite");

// Parameter sweeps: in a sweep file any value of any geometry may be a list of values instead of
// one, per-layer keys included,
//   [medium]
//   albedo = [0.5, 0.9]
//   g = [0, 0.9]
// and the file stands for every combination (here four scenes), each read and validated as a
// scene. A key whose value is itself a list (source.origin = [x, y, z]) is swept by a list of such
// lists. Combinations are ordered as the lists appear in the file, the last varying fastest.
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
                                    Validation validation = Validation::on_read,
                                    std::string_view default_geometry = "infinite");
std::vector<SweepPoint> load_sweep(const std::filesystem::path& path,
                                   Validation validation = Validation::on_read,
                                   std::string_view default_geometry = "infinite");

}  // namespace scatterlab
