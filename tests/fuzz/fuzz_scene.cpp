// Scene files (TOML) as simulate, searchlight, render and the Python module read them: the text
// through every scene reader, each spec validated and its memory checked as before a run, and a
// mesh scene's [mesh] table built into its mesh (io/scene.hpp, render/render_scene.hpp).

#include <toml++/toml.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <variant>

#include "fuzz_support.hpp"
#include "scatterlab/io/scene.hpp"
#include "scatterlab/mesh/lit_mesh.hpp"
#include "scatterlab/render/render_scene.hpp"
#include "scatterlab/transport/engine.hpp"
#include "scatterlab/transport/layered_slab.hpp"
#include "scatterlab/transport/lit_object.hpp"
#include "scatterlab/transport/searchlight.hpp"
#include "scatterlab/transport/simulate.hpp"

namespace {

using namespace scatterlab;

const std::string kOrigin = "fuzz.toml";

// An OBJ file the scenes may name (mesh.path = "mesh.obj"), in the working folder.
constexpr const char* kMesh =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// Only a plain file name in the working folder may be opened: an absolute path or one that climbs
// out would let an input read any file of the machine (a device or a FIFO among them).
bool stays_inside(const toml::table& root) {
  const toml::node_view<const toml::node> path = root["mesh"]["path"];
  if (!path.is_string()) return true;
  const std::filesystem::path file(path.as_string()->get());
  return file.has_filename() && file == file.filename() && file != "..";
}

// A procedural mesh of more than 2^15 triangles takes seconds to build and check under the
// sanitizers (a minute for the 2 million of a sphere of 1024 x 1024): the same code run longer.
// Those the program refuses by its memory estimate (render_scene.cpp: 336 bytes a triangle, over
// the 2 GiB of fuzz::limit_memory) are refused at once, and stay in.
bool small_or_refused_mesh(const toml::table& root) {
  const toml::node_view<const toml::node> mesh = root["mesh"];
  const bool bumpy = mesh["shape"].value<std::string>() == "bumpy_sphere";
  const double triangles = 2.0 * mesh["rings"].value<double>().value_or(bumpy ? 71 : 24) *
                           mesh["segments"].value<double>().value_or(bumpy ? 72 : 48);
  return triangles <= 0x1p15 || triangles * 336 > 0x1p31;
}

// Whether an input is run: kept to what stays inside the working folder and ends in seconds.
bool runs_here(std::string_view text) {
  toml::table root;
  try {
    root = toml::parse(text, kOrigin);
  } catch (const toml::parse_error&) {
    return true;  // the readers refuse it before any file is opened
  }
  return stays_inside(root) && small_or_refused_mesh(root);
}

void check_memory(const TransportProblem& problem) {
  check_transport_memory(problem, /*ranks=*/1, /*resuming=*/false);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  fuzz::write_input("mesh.obj", kMesh);  // makes the working folder, the mesh's base
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::text_of(data, size);
  if (!runs_here(text)) return -1;  // kept out of the corpus
  const std::filesystem::path& base = fuzz::work_folder();

  // simulate and searchlight: every geometry and its sweeps (a file without lists is one
  // point), built and checked as sim/cli/scene_command.cpp does before a run.
  for (const std::string_view geometry : {"infinite", "half_space"}) {
    fuzz::expect_clean([&] {
      for (SweepPoint& point : parse_sweep(text, kOrigin, Validation::on_read, geometry)) {
        Scene& scene = point.scene;
        if (scene.mesh_text) {
          auto& spec = std::get<LitObjectSpec>(scene.spec);
          SceneMesh mesh = parse_scene_mesh(*scene.mesh_text, kOrigin, base);
          spec.mesh_source = std::move(mesh.source);
          spec.mesh = std::make_shared<const TriangleMesh>(std::move(mesh.mesh));
          spec.validate();
          check_lit_mesh(spec);
        }
        std::visit([](const auto& spec) { check_memory(transport_problem(spec)); }, scene.spec);
      }
    });
  }
  // render.
  fuzz::expect_clean([&] { (void)parse_render_scene(text, kOrigin, base); });
  return 0;
}
