#include "adapters/load_occluder.h"

#include "adapters/obj_reader.h"
#include "adapters/text_input.h"
#include "osd_cull/error.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace osd_cull::adapters {

frame::TriangleMesh loadTriangleMesh(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".obj")
    throw Error(path.string() + ": occluders are read from OBJ files (got '" + ext + "')");
  // The OBJ reader checks syntax and indices; the cage rules (manifold, orientation) are
  // not applied, as an occluder only needs triangles.
  const CageMesh cage = detail::readObj(detail::readFileBytes(path), path, Scheme::Bilinear, false);
  std::vector<bool> hole(cage.faceSizes.size(), false);
  for (int f : cage.holes) hole.at(static_cast<size_t>(f)) = true;
  frame::TriangleMesh mesh;
  mesh.positions = cage.positions;
  size_t offset = 0;
  for (size_t f = 0; f < cage.faceSizes.size(); ++f) {
    const auto n = static_cast<size_t>(cage.faceSizes[f]);
    if (!hole[f])
      for (size_t k = 1; k + 1 < n; ++k)
        for (size_t c : {size_t{0}, k, k + 1})
          mesh.indices.push_back(static_cast<uint32_t>(cage.faceVertices[offset + c]));
    offset += n;
  }
  if (mesh.indices.empty()) throw Error(path.string() + ": no triangles to draw");
  return mesh;
}

}  // namespace osd_cull::adapters
