#pragma once
// The explorer's BSSRDF on a mesh (Bitterli 2013 §3.1.2, §3.6): the hierarchical point cloud of
// render/point_cloud.hpp and render/point_octree.hpp on a built-in mesh or an OBJ file of an open
// folder, lit by a directional light the page rotates, and the multiple-scattering exitance M at
// the vertices of the mesh the page draws. Private to the explore module; api.hpp lists its
// paths. Without the render component (SCATTERLAB_WITH_RENDER off) both answer 501.

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "scatterlab/explore/text_model.hpp"

namespace scatterlab {

class MeshView {
 public:
  explicit MeshView(std::vector<std::filesystem::path> open_folders);
  ~MeshView();
  MeshView(const MeshView&) = delete;
  MeshView& operator=(const MeshView&) = delete;

  // GET /api/meshes: the built-in shapes with their parameters' defaults, the OBJ files of the
  // open folders, the request's defaults and limits.
  std::string meshes() const;
  // POST /api/mesh_exitance (api.hpp): a built-in model, or one of `text_models` by name.
  std::string exitance(std::string_view body, const std::vector<TextModel>& text_models) const;

 private:
  struct Cache;
  std::vector<std::filesystem::path> open_folders_;
  std::unique_ptr<Cache> cache_;
};

}  // namespace scatterlab
