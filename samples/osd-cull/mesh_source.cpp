#include "mesh_source.h"

#include "option_checks.h"

#include "adapters/load_mesh.h"
#include "adapters/unused_vertices.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/procedural.h"

namespace osd_cull::cli {

void addMeshOptions(CLI::App& app, MeshSource& source) {
  app.add_option_function<std::vector<std::string>>(
         "MESH",
         [&source](const std::vector<std::string>& paths) {
           if (paths.size() > 1)
             throw CLI::ValidationError("MESH",
                                        "expected at most one MESH, got '" + paths[1] + "' too");
           source.path = paths.front();
         },
         "OBJ (with OpenSubdiv tags), OFF, PLY, STL (Catmull-Clark cages, refined\n"
         "adaptively into Bezier and Gregory patches) or BPT (Bezier patches, used as\n"
         "they are); default: a built-in mesh generated in code")
      ->type_name("");
  app.add_option_function<std::string>(
         "--scheme", [&source](const std::string& name) { source.scheme = schemeFromString(name); },
         "override the subdivision scheme (default: file-name prefix catmark_,\n"
         "loop_ or bilinear_, else catmark)")
      ->type_name("S")
      ->check(oneOf({"catmark", "loop", "bilinear"}));
}

void addPatchOptions(CLI::App& app, PatchOptions& options) {
  app.add_option("--level", options.isolationLevel, "adaptive isolation level, 0..10 (default 2)")
      ->type_name("N")
      ->check(integerIn(0, 10));
  app.add_option_function<std::string>(
         "--endcap",
         [&options](const std::string& name) {
           options.endCaps = name == "bspline" ? EndCap::BSplineBasis : EndCap::GregoryBasis;
         },
         "end caps of irregular patches: gregory (default) or bspline")
      ->type_name("E")
      ->check(oneOf({"gregory", "bspline"}));
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
    mesh.droppedVertices = adapters::dropUnusedVertices(*mesh.cage);
  }
  return mesh;
}

}  // namespace osd_cull::cli
