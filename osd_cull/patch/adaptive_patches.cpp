#include "osd_cull/patch/adaptive_patches.h"

#include "osd_cull/error.h"

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <chrono>
#include <string>

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

void buildRefinedStencils(const Far::TopologyRefiner& refiner, AdaptivePatches& out) {
  const auto start = Clock::now();
  using StencilFactory = Far::StencilTableFactoryReal<double>;
  StencilFactory::Options stencilOptions;
  stencilOptions.interpolationMode = StencilFactory::INTERPOLATE_VERTEX;
  stencilOptions.generateOffsets = true;
  stencilOptions.generateControlVerts = true;        // rows for level-0 vertices too
  stencilOptions.generateIntermediateLevels = true;  // adaptive patches use every level
  stencilOptions.factorizeIntermediateLevels = true;
  out.refinedStencils.reset(StencilFactory::Create(refiner, stencilOptions));
  out.stencilMs = msSince(start);
  if (!out.refinedStencils) throw Error("OpenSubdiv could not build the refinement stencils");
  if (out.refinedStencils->GetNumStencils() != out.refinedVertexCount)
    throw Error("buildAdaptivePatches: " + std::to_string(out.refinedStencils->GetNumStencils()) +
                " refinement stencils for " + std::to_string(out.refinedVertexCount) + " vertices");
}

}  // namespace

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
  out.localPointCount = out.patchTable->GetNumLocalPoints();
  if (options.pointMatrix) buildRefinedStencils(refiner, out);
  if (out.localPointCount > 0) {
    if (!out.patchTable->LocalPointStencilPrecisionMatchesType<double>())
      throw Error("buildAdaptivePatches: OpenSubdiv built single-precision local-point stencils");
    out.localPointStencils = out.patchTable->GetLocalPointStencilTable<double>();
    if (!out.localPointStencils || out.localPointStencils->GetNumStencils() != out.localPointCount)
      throw Error("buildAdaptivePatches: the patch table has " +
                  std::to_string(out.localPointCount) + " local points but no stencil for each");
    for (int index : out.localPointStencils->GetControlIndices())
      if (index < 0 || index >= out.refinedVertexCount)
        throw Error("buildAdaptivePatches: a local-point stencil uses point " +
                    std::to_string(index) + ", not a refined vertex");
  }
  return out;
}

}  // namespace osd_cull
