#include "mesh_source.h"

#include "adapters/load_mesh.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/procedural.h"

namespace osd_cull::cli {

MeshSource meshSourceFromArgs(Args& args) {
  MeshSource source;
  if (auto scheme = args.value("scheme")) {
    source.scheme = schemeFromString(*scheme);
    if (!source.scheme)
      throw Error("option --scheme: '" + *scheme + "' is not one of catmark, loop, bilinear");
  }
  const auto& pos = args.positional();
  if (pos.size() > 1) throw Error("expected at most one MESH, got '" + pos[1] + "' too");
  if (!pos.empty()) source.path = pos[0];
  return source;
}

PatchOptions patchOptionsFromArgs(Args& args) {
  PatchOptions options;
  if (auto level = args.integer("level", 0, 10)) options.isolationLevel = static_cast<int>(*level);
  if (auto endcap = args.value("endcap")) {
    if (*endcap == "gregory")
      options.endCaps = EndCap::GregoryBasis;
    else if (*endcap == "bspline")
      options.endCaps = EndCap::BSplineBasis;
    else
      throw Error("option --endcap: '" + *endcap + "' is not one of gregory, bspline");
  }
  return options;
}

LoadedMesh loadMeshSource(const MeshSource& source) {
  LoadedMesh mesh;
  if (!source.path) {
    mesh.cage = scene::defaultMesh();
    if (source.scheme) mesh.cage->scheme = *source.scheme;
    mesh.name = mesh.cage->source;
    return mesh;
  }
  mesh.name = *source.path;
  if (adapters::isBezierPatchFile(*source.path)) {
    if (source.scheme) throw Error("option --scheme does not apply to Bezier patch files");
    mesh.bezier = adapters::loadBezierPatches(*source.path);
  } else {
    adapters::LoadOptions options;
    options.scheme = source.scheme;
    mesh.cage = adapters::loadCage(*source.path, options);
  }
  return mesh;
}

}  // namespace osd_cull::cli
