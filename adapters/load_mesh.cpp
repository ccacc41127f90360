#include "adapters/load_mesh.h"

#include "adapters/coordinate_limit.h"
#include "adapters/obj_reader.h"
#include "adapters/off_reader.h"
#include "adapters/openmesh_reader.h"
#include "adapters/text_input.h"
#include "adapters/topology_notes.h"
#include "osd_cull/error.h"

#include <algorithm>

namespace osd_cull::adapters {

bool isBezierPatchFile(const std::filesystem::path& path) {
  return detail::lowerExtension(path) == ".bpt";
}

std::vector<std::string> cageFileExtensions() {
  std::vector<std::string> ext = {".obj", ".off"};
  if (detail::haveOpenMesh()) ext.insert(ext.end(), {".ply", ".stl"});
  return ext;
}

CageMesh loadCage(const std::filesystem::path& path, const LoadOptions& options) {
  const std::string file = path.string();
  const std::string ext = detail::lowerExtension(path);
  if (ext == ".bpt")
    throw Error(file +
                ": a BPT file holds Bézier patches, not a control cage (use loadBezierPatches)");
  const std::vector<std::string> known = cageFileExtensions();
  if (std::find(known.begin(), known.end(), ext) == known.end() && ext != ".ply" && ext != ".stl") {
    std::string list;
    for (const std::string& e : known) list += (list.empty() ? "" : ", ") + e;
    throw Error(file + ": unknown mesh format " + detail::quote(ext) + "; expected " + list +
                " or .bpt");
  }
  const Scheme scheme =
      options.scheme ? *options.scheme : schemeFromFileName(file).value_or(Scheme::CatmullClark);

  CageMesh mesh = [&] {  // the file's bytes are released before the checks below
    const std::string bytes = detail::readFileBytes(path);
    if (ext == ".obj") return detail::readObj(bytes, path, scheme, options.leftHanded);
    if (ext == ".off")
      return detail::isBinaryOff(bytes) ? detail::readBinaryOff(bytes, file, scheme)
                                        : detail::readOff(bytes, file, scheme);
    return detail::readWithOpenMesh(path, bytes, scheme);
  }();

  checkCoordinateRange(mesh.positions, file);  // OFF, PLY, STL (OBJ checks per line)
  checkExtent(mesh.positions, file);
  validate(mesh);  // the readers check as they go; this is the library's own contract
  noteTopology(mesh);
  return mesh;
}

}  // namespace osd_cull::adapters
