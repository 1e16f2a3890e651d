// OBJ meshes as render and mesh scenes read them (render/obj_mesh.hpp), with the file's normals
// and with flat ones, then checked as a render scene's mesh is (mesh/mesh_checks.hpp): closed, no
// triangle of zero area, a positive volume, no part through another.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "render/obj_mesh.hpp"
#include "scatterlab/mesh/mesh_checks.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scatterlab::fuzz::limit_memory();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace scatterlab;
  const std::string text(fuzz::text_of(data, size));
  for (const bool interpolated : {true, false}) {
    fuzz::expect_clean([&] {
      const TriangleMesh mesh = parse_obj_mesh(text, "fuzz.obj", interpolated);
      mesh.validate();
      require_closed_mesh(mesh);
      require_enclosed_volume(mesh);
      require_no_self_intersection(mesh);
    });
  }
  return 0;
}
