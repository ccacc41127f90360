#include "osd_cull/patch/adaptive_patches.h"

#include "osd_cull/error.h"
#include "osd_cull/patch/point_matrix.h"

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <chrono>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void checkScheme(const Far::TopologyRefiner& refiner) {
  switch (refiner.GetSchemeType()) {
    case OpenSubdiv::Sdc::SCHEME_CATMARK:
      return;
    case OpenSubdiv::Sdc::SCHEME_LOOP:
      throw Error(
          "Loop patches are not extracted yet: osd_cull draws Bézier and Gregory quad patches; "
          "use a Catmull-Clark mesh (catmark)");
    case OpenSubdiv::Sdc::SCHEME_BILINEAR:
      throw Error(
          "bilinear patches are not extracted yet: osd_cull draws Bézier and Gregory quad patches; "
          "use a Catmull-Clark mesh (catmark)");
  }
  throw Error("unknown subdivision scheme; only Catmull-Clark patches are extracted");
}

void checkLevelZeroFaces(const Far::TopologyRefiner& refiner) {
  const Far::TopologyLevel& base = refiner.GetLevel(0);
  for (int f = 0; f < base.GetNumFaces(); ++f)
    if (!base.IsFaceHole(f) && base.GetFaceVertices(f).size() != 4)
      throw Error("isolation level 0: face " + std::to_string(f) + " has " +
                  std::to_string(base.GetFaceVertices(f).size()) +
                  " vertices; OpenSubdiv makes patches for non-quad faces only from level 1 on");
}

// What to change in the application's patch table options for a type osd_cull cannot use.
std::string typeAdvice(Far::PatchDescriptor::Type type) {
  using D = Far::PatchDescriptor;
  if (type == D::QUADS || type == D::TRIANGLES)
    return "the refiner was refined uniformly; refine it adaptively (RefineAdaptive)";
  if (type == D::GREGORY || type == D::GREGORY_BOUNDARY)
    return "legacy Gregory end caps; build the table with ENDCAP_GREGORY_BASIS or "
           "ENDCAP_BSPLINE_BASIS";
  if (type == D::GREGORY_TRIANGLE || type == D::LOOP)
    return "Loop (triangle) patches; osd_cull draws Catmull-Clark quad patches";
  return "osd_cull extracts REGULAR and GREGORY_BASIS patches only";
}

// Local-point stencils of `table` in double: its own when it has double ones, else a
// widened copy kept in out.convertedLocalPointStencils. Checks they index refined vertices.
void attachLocalPointStencils(AdaptivePatches& out, const Far::PatchTable& table,
                              const char* where) {
  out.localPointCount = table.GetNumLocalPoints();
  if (out.localPointCount == 0) return;
  if (table.LocalPointStencilPrecisionMatchesType<double>()) {
    out.localPointStencils = table.GetLocalPointStencilTable<double>();
  } else if (const auto* f = table.GetLocalPointStencilTable<float>()) {
    std::vector<double> weights(f->GetWeights().begin(), f->GetWeights().end());
    out.convertedLocalPointStencils = PatchPointMatrix(out.refinedVertexCount, f->GetSizes(),
                                                       f->GetControlIndices(), std::move(weights))
                                          .toFarStencilTableDouble();
    out.localPointStencils = out.convertedLocalPointStencils.get();
  }
  if (!out.localPointStencils || out.localPointStencils->GetNumStencils() != out.localPointCount)
    throw Error(std::string(where) + ": the patch table has " +
                std::to_string(out.localPointCount) + " local points but no stencil for each");
  for (int index : out.localPointStencils->GetControlIndices())
    if (index < 0 || index >= out.refinedVertexCount)
      throw Error(std::string(where) + ": a local-point stencil uses point " +
                  std::to_string(index) + ", not a refined vertex");
}

void buildRefinedStencils(const Far::TopologyRefiner& refiner, AdaptivePatches& out) {
  const auto start = Clock::now();
  out.refinedStencils = refinementStencils(refiner);
  out.stencilMs = msSince(start);
  if (out.refinedStencils->GetNumStencils() != out.refinedVertexCount)
    throw Error("buildAdaptivePatches: " + std::to_string(out.refinedStencils->GetNumStencils()) +
                " refinement stencils for " + std::to_string(out.refinedVertexCount) + " vertices");
}

}  // namespace

std::unique_ptr<const Far::StencilTableReal<double>> refinementStencils(
    const Far::TopologyRefiner& refiner) {
  using StencilFactory = Far::StencilTableFactoryReal<double>;
  StencilFactory::Options stencilOptions;
  stencilOptions.interpolationMode = StencilFactory::INTERPOLATE_VERTEX;
  stencilOptions.generateOffsets = true;
  stencilOptions.generateControlVerts = true;        // rows for level-0 vertices too
  stencilOptions.generateIntermediateLevels = true;  // adaptive patches use every level
  stencilOptions.factorizeIntermediateLevels = true;
  std::unique_ptr<const Far::StencilTableReal<double>> table(
      StencilFactory::Create(refiner, stencilOptions));
  if (!table) throw Error("OpenSubdiv could not build the refinement stencils");
  return table;
}

void checkPatchOptions(const PatchOptions& options) {
  if (options.isolationLevel < 0 || options.isolationLevel > 10)
    throw Error("patch options: isolation level " + std::to_string(options.isolationLevel) +
                " is out of range [0, 10]");
  if (options.secondaryLevel &&
      (*options.secondaryLevel < 0 || *options.secondaryLevel > options.isolationLevel))
    throw Error("patch options: secondary level " + std::to_string(*options.secondaryLevel) +
                " is out of range [0, isolation level " + std::to_string(options.isolationLevel) +
                "]");
}

AdaptivePatches buildAdaptivePatches(Far::TopologyRefiner& refiner, const PatchOptions& options) {
  checkPatchOptions(options);
  checkScheme(refiner);
  if (refiner.GetMaxLevel() != 0 || refiner.GetNumLevels() != 1)
    throw Error(
        "buildAdaptivePatches: the refiner is already refined; pass a fresh base-level refiner");
  if (options.isolationLevel == 0) checkLevelZeroFaces(refiner);

  Far::PatchTableFactory::Options patchOptions(static_cast<unsigned>(options.isolationLevel));
  patchOptions.SetEndCapType(options.endCaps == EndCap::BSplineBasis
                                 ? Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS
                                 : Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  patchOptions.useInfSharpPatch = options.infSharpPatches;
  patchOptions.useSingleCreasePatch = false;  // single-crease patches are not Bézier patches
  patchOptions.shareEndCapPatchPoints = true;
  patchOptions.generateVaryingTables = false;
  patchOptions.generateVaryingLocalPoints = false;
  // Texture coordinates (face_varying_uv.h): OpenSubdiv's linear face-varying patches,
  // which leave the vertex refinement unchanged (considerFVarChannels stays false).
  patchOptions.generateFVarTables = refiner.GetNumFVarChannels() > 0;
  patchOptions.generateFVarLegacyLinearPatches = true;
  patchOptions.SetPatchPrecision<double>();

  AdaptivePatches out;
  auto start = Clock::now();
  Far::TopologyRefiner::AdaptiveOptions adaptive = patchOptions.GetRefineAdaptiveOptions();
  if (options.secondaryLevel) adaptive.SetSecondaryLevel(*options.secondaryLevel);
  refiner.RefineAdaptive(adaptive);
  out.refineMs = msSince(start);

  start = Clock::now();
  out.patchTable.reset(Far::PatchTableFactory::Create(refiner, patchOptions));
  out.patchTableMs = msSince(start);
  if (!out.patchTable) throw Error("OpenSubdiv could not build the patch table");

  out.refinedVertexCount = refiner.GetNumVerticesTotal();
  if (options.pointMatrix) buildRefinedStencils(refiner, out);
  if (out.patchTable->GetNumLocalPoints() > 0 &&
      !out.patchTable->LocalPointStencilPrecisionMatchesType<double>())
    throw Error("buildAdaptivePatches: OpenSubdiv built single-precision local-point stencils");
  attachLocalPointStencils(out, *out.patchTable, "buildAdaptivePatches");
  return out;
}

AdaptivePatches adoptPatchTable(const Far::TopologyRefiner& refiner, const Far::PatchTable& table) {
  const char* where = "adoptPatchTable";
  checkScheme(refiner);
  if (refiner.IsUniform())
    throw Error(std::string(where) + ": " + typeAdvice(Far::PatchDescriptor::QUADS));
  // Patch points are refined vertices of this refiner, then the table's local points.
  const int points = refiner.GetNumVerticesTotal() + table.GetNumLocalPoints();
  for (const Far::Index index : table.GetPatchControlVerticesTable())
    if (index < 0 || index >= points)
      throw Error(std::string(where) + ": the patch table uses point " + std::to_string(index) +
                  ", the refiner has " + std::to_string(refiner.GetNumVerticesTotal()) +
                  " refined vertices and the table " + std::to_string(table.GetNumLocalPoints()) +
                  " local points (a table of another refiner, or the refiner was refined again)");
  for (int a = 0; a < table.GetNumPatchArrays(); ++a) {
    const Far::PatchDescriptor::Type type = table.GetPatchArrayDescriptor(a).GetType();
    if (type != Far::PatchDescriptor::REGULAR && type != Far::PatchDescriptor::GREGORY_BASIS)
      throw Error(std::string(where) + ": patch array " + std::to_string(a) + " has type " +
                  std::to_string(static_cast<int>(type)) + ": " + typeAdvice(type));
  }
  for (Far::Index sharpness : table.GetSharpnessIndexTable())
    if (sharpness >= 0)
      throw Error(std::string(where) +
                  ": the table has single-crease patches; build it with useSingleCreasePatch = "
                  "false (their sharp B-spline basis has no Bézier form here)");

  AdaptivePatches out;
  out.patchTable = std::shared_ptr<const Far::PatchTable>(&table, [](const Far::PatchTable*) {});
  const auto start = Clock::now();
  out.refinedStencils = refinementStencils(refiner);
  out.stencilMs = msSince(start);
  out.refinedVertexCount = refiner.GetNumVerticesTotal();
  if (out.refinedStencils->GetNumStencils() != out.refinedVertexCount)
    throw Error(std::string(where) + ": " + std::to_string(out.refinedStencils->GetNumStencils()) +
                " refinement stencils for " + std::to_string(out.refinedVertexCount) + " vertices");
  attachLocalPointStencils(out, table, where);
  return out;
}

}  // namespace osd_cull
