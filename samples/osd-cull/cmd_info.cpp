// `osd-cull info`: what a mesh is and what osd_cull makes of it.
#include "command.h"
#include "mesh_source.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace osd_cull::cli {
namespace {

const char* kDescription =
    R"(Prints what a mesh is and what osd_cull extracts from it: scheme, vertices, faces, closed
or open, non-manifold counts, patches by kind (regular, boundary, corner, Gregory),
control points and the time each step took. With no MESH, a built-in mesh generated in
code is used.)";

/// \brief The parsed options of `osd-cull info`.
struct InfoArgs {
  MeshSource source;
  PatchOptions patchOptions;
  bool json = false;
};

std::string originCounts(const ExtractionStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "regular %u, boundary %u, corner %u, b-spline end caps %u",
                s.regular, s.boundary, s.corner, s.bsplineEndCaps);
  return buf;
}

/// \brief The description of a mesh of Bézier patches (a BPT file): its patches as given.
void describeBezier(nlohmann::ordered_json& out, const PatchSet& p, double loadMs) {
  out["format"] = "bezier patches";
  out["scheme"] = "bezier";
  out["vertices"] = p.points.size();
  out["faces"] = p.patchCount();
  out["closed"] = false;
  out["patches"] = {
      {"total", p.patchCount()}, {"bezier", p.bezierCount}, {"gregory", p.gregoryCount}};
  out["control_points"] = p.points.size();
  out["timing_ms"] = {{"load", loadMs}};
}

/// \brief The patches extracted from a cage and the time of each step; with `text`, also the
/// origin counts for the text form ("_origins"). A cage whose patches cannot be extracted
/// (Loop, bilinear) gets null patches and the reason.
void describeExtraction(nlohmann::ordered_json& out, const CageMesh& cage,
                        const PatchOptions& patchOptions, double loadMs, bool text) {
  try {
    const PatchExtraction ex = extractPatches(cage, patchOptions);
    const ExtractionStats& st = ex.stats;
    out["patches"] = {{"total", ex.patches.patchCount()},
                      {"bezier", ex.patches.bezierCount},
                      {"gregory", ex.patches.gregoryCount},
                      {"regular", st.regular},
                      {"boundary", st.boundary},
                      {"corner", st.corner},
                      {"bspline_end_caps", st.bsplineEndCaps}};
    out["control_points"] = st.controlPoints;
    out["matrix_non_zeros"] = st.matrixNonZeros;
    out["timing_ms"] = {{"load", loadMs},
                        {"topology", st.topologyMs},
                        {"refine", st.refineMs},
                        {"patch_table", st.patchTableMs},
                        {"stencils", st.stencilMs},
                        {"matrix", st.matrixMs},
                        {"extract_total", st.totalMs}};
    if (text) out["_origins"] = originCounts(st);
  } catch (const Error& e) {
    // Loop and bilinear cages load and are described; their patches are not extracted.
    out["patches"] = nullptr;
    out["patches_error"] = e.what();
    out["timing_ms"] = {{"load", loadMs}};
  }
}

/// \brief The description of a cage: its topology, the refinement options and what
/// extraction makes of it (describeExtraction), and the loader's notes.
void describeCage(nlohmann::ordered_json& out, const LoadedMesh& mesh,
                  const PatchOptions& patchOptions, double loadMs, bool text) {
  const CageMesh& cage = *mesh.cage;
  const auto refiner = makeTopologyRefiner(cage);
  const TopologySummary s = summarize(*refiner);
  out["format"] = "cage";
  out["scheme"] = std::string(toString(cage.scheme));
  out["vertices"] = s.vertices + static_cast<int>(mesh.droppedVertices);  // as in the file
  out["faces"] = s.faces;
  out["edges"] = s.edges;
  out["face_sizes"] = {{"triangles", s.triangles}, {"quads", s.quads}, {"other", s.otherFaces}};
  out["closed"] = s.closed;
  out["boundary_edges"] = s.boundaryEdges;
  out["holes"] = s.holes;
  out["non_manifold_edges"] = s.nonManifoldEdges;
  out["non_manifold_vertices"] = s.nonManifoldVertices;
  out["unused_vertices"] = s.unusedVertices + static_cast<int>(mesh.droppedVertices);
  out["degenerate_faces"] = s.degenerateFaces;
  out["creased_edges"] = s.creasedEdges;
  out["corner_vertices"] = s.cornerVertices;
  out["max_valence"] = s.maxValence;
  out["extraordinary_vertices"] = s.extraordinaryVertices;
  out["level"] = patchOptions.isolationLevel;
  out["endcap"] = patchOptions.endCaps == EndCap::GregoryBasis ? "gregory" : "bspline";
  describeExtraction(out, cage, patchOptions, loadMs, text);
  out["notes"] = cage.notes;
}

/// \brief One `KEY VALUE` line of the text form.
void printLine(const char* key, const std::string& value) {
  std::printf("%-15s %s\n", key, value.c_str());
}

/// \brief The text lines of a cage's topology and refinement.
void printCage(nlohmann::ordered_json& out, const PatchOptions& patchOptions) {
  printLine("vertices", std::to_string(out["vertices"].get<int>()) + " (" +
                            std::to_string(out["unused_vertices"].get<int>()) + " unused)");
  printLine("faces", std::to_string(out["faces"].get<int>()) + " (" +
                         std::to_string(out["face_sizes"]["quads"].get<int>()) + " quads, " +
                         std::to_string(out["face_sizes"]["triangles"].get<int>()) +
                         " triangles, " + std::to_string(out["face_sizes"]["other"].get<int>()) +
                         " other; " + std::to_string(out["degenerate_faces"].get<int>()) +
                         " repeat a vertex; " + std::to_string(out["holes"].get<int>()) +
                         " holes)");
  printLine("surface",
            out["closed"].get<bool>()
                ? std::string("closed")
                : "open (" + std::to_string(out["boundary_edges"].get<int>()) + " boundary edges)");
  printLine("non-manifold", std::to_string(out["non_manifold_edges"].get<int>()) + " edges, " +
                                std::to_string(out["non_manifold_vertices"].get<int>()) +
                                " vertices");
  printLine("features", std::to_string(out["creased_edges"].get<int>()) + " creased edges, " +
                            std::to_string(out["corner_vertices"].get<int>()) + " corners, " +
                            std::to_string(out["extraordinary_vertices"].get<int>()) +
                            " extraordinary vertices, max valence " +
                            std::to_string(out["max_valence"].get<int>()));
  printLine("refinement", "adaptive level " + std::to_string(patchOptions.isolationLevel) + ", " +
                              out["endcap"].get<std::string>() + " end caps");
}

/// \brief The text lines of the patches (or why there are none), the timings and the notes.
void printPatches(nlohmann::ordered_json& out) {
  if (out["patches"].is_null()) {
    printLine("patches", "none: " + out["patches_error"].get<std::string>());
  } else {
    printLine("patches", std::to_string(out["patches"]["total"].get<int>()) + " = " +
                             std::to_string(out["patches"]["bezier"].get<int>()) + " Bezier + " +
                             std::to_string(out["patches"]["gregory"].get<int>()) + " Gregory");
    if (out.contains("_origins")) printLine("", "Bezier: " + out["_origins"].get<std::string>());
    printLine("control points", std::to_string(out["control_points"].get<int>()));
  }
  std::string timing;
  for (const auto& [k, v] : out["timing_ms"].items()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%s %.2f", timing.empty() ? "" : ", ", k.c_str(),
                  v.get<double>());
    timing += buf;
  }
  printLine("time (ms)", timing);
  if (out.contains("notes"))
    for (const auto& n : out["notes"]) printLine("note", n.get<std::string>());
}

int runInfo(const InfoArgs& args) {
  const auto t0 = std::chrono::steady_clock::now();
  LoadedMesh mesh = loadMeshSource(args.source);
  const double loadMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  nlohmann::ordered_json out;
  out["mesh"] = mesh.name;
  if (mesh.bezier)
    describeBezier(out, *mesh.bezier, loadMs);
  else
    describeCage(out, mesh, args.patchOptions, loadMs, !args.json);

  if (args.json) {
    out.erase("_origins");
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  printLine("mesh", out["mesh"].get<std::string>() + " (" + out["format"].get<std::string>() + ")");
  printLine("scheme", out["scheme"].get<std::string>());
  if (mesh.cage) printCage(out, args.patchOptions);
  printPatches(out);
  return 0;
}

Runner setupInfo(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  addMeshOptions(app, args->source);
  addPatchOptions(app, args->patchOptions);
  app.add_flag("--json", args->json, "print one JSON object instead of text");
  return [args] { return runInfo(*args); };
}

const Registration kInfo({"info", "describe a mesh and the patches osd_cull extracts from it",
                          kDescription, setupInfo});

}  // namespace
}  // namespace osd_cull::cli
