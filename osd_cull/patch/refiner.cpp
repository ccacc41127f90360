#include "osd_cull/patch/refiner.h"

#include "osd_cull/error.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <mutex>
#include <string>

namespace osd_cull {
namespace {

namespace Sdc = OpenSubdiv::Sdc;

// OpenSubdiv reports topology errors through a global callback; collect them per thread
// so the exception can quote them.
thread_local std::string tlsOsdErrors;

void collectOsdError(Far::ErrorType, const char* message) {
  if (!tlsOsdErrors.empty()) tlsOsdErrors += "; ";
  tlsOsdErrors += message ? message : "(no message)";
}

Sdc::SchemeType sdcScheme(Scheme s) {
  switch (s) {
    case Scheme::Loop:
      return Sdc::SCHEME_LOOP;
    case Scheme::Bilinear:
      return Sdc::SCHEME_BILINEAR;
    case Scheme::CatmullClark:
      break;
  }
  return Sdc::SCHEME_CATMARK;
}

Sdc::Options sdcOptions(const CageMesh& mesh) {
  Sdc::Options o;
  switch (mesh.boundary) {
    case BoundaryInterpolation::None:
      o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE);
      break;
    case BoundaryInterpolation::EdgeOnly:
      o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
      break;
    case BoundaryInterpolation::EdgeAndCorner:
      o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
      break;
  }
  switch (mesh.fvarBoundary) {
    case FVarInterpolation::None:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_NONE);
      break;
    case FVarInterpolation::CornersOnly:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_CORNERS_ONLY);
      break;
    case FVarInterpolation::CornersPlus1:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_CORNERS_PLUS1);
      break;
    case FVarInterpolation::CornersPlus2:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_CORNERS_PLUS2);
      break;
    case FVarInterpolation::Boundaries:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_BOUNDARIES);
      break;
    case FVarInterpolation::All:
      o.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
      break;
  }
  o.SetCreasingMethod(mesh.creasing == CreasingMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                               : Sdc::Options::CREASE_UNIFORM);
  o.SetTriangleSubdivision(mesh.triangles == TriangleSubdivision::Smooth
                               ? Sdc::Options::TRI_SUB_SMOOTH
                               : Sdc::Options::TRI_SUB_CATMARK);
  return o;
}

}  // namespace

std::unique_ptr<Far::TopologyRefiner> makeTopologyRefiner(const CageMesh& mesh) {
  validate(mesh);
  if (mesh.scheme == Scheme::Loop)
    for (int n : mesh.faceSizes)
      if (n != 3)
        throw Error(mesh.source + ": the Loop scheme needs triangles; found a face with " +
                    std::to_string(n) + " vertices");

  std::vector<int> creasePairs;
  std::vector<float> creaseWeights;
  creasePairs.reserve(mesh.creases.size() * 2);
  for (const CreaseEdge& c : mesh.creases) {
    creasePairs.push_back(c.v0);
    creasePairs.push_back(c.v1);
    creaseWeights.push_back(c.sharpness);
  }
  std::vector<int> cornerIndices;
  std::vector<float> cornerWeights;
  for (const CornerVertex& c : mesh.corners) {
    cornerIndices.push_back(c.vertex);
    cornerWeights.push_back(c.sharpness);
  }

  Far::TopologyDescriptor desc;
  desc.numVertices = mesh.vertexCount();
  desc.numFaces = mesh.faceCount();
  desc.numVertsPerFace = mesh.faceSizes.data();
  desc.vertIndicesPerFace = mesh.faceVertices.data();
  desc.numCreases = static_cast<int>(mesh.creases.size());
  desc.creaseVertexIndexPairs = creasePairs.data();
  desc.creaseWeights = creaseWeights.data();
  desc.numCorners = static_cast<int>(mesh.corners.size());
  desc.cornerVertexIndices = cornerIndices.data();
  desc.cornerWeights = cornerWeights.data();
  desc.numHoles = static_cast<int>(mesh.holes.size());
  desc.holeIndices = mesh.holes.data();
  // Texture coordinates become face-varying channel 0 (face_varying_uv.h).
  Far::TopologyDescriptor::FVarChannel uvChannel;
  if (mesh.hasUVs()) {
    uvChannel.numValues = static_cast<int>(mesh.uvs.size());
    uvChannel.valueIndices = mesh.faceUVs.data();
    desc.numFVarChannels = 1;
    desc.fvarChannels = &uvChannel;
  }

  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  Factory::Options options(sdcScheme(mesh.scheme), sdcOptions(mesh));

  static std::mutex callbackMutex;  // the callback is process-global
  std::unique_ptr<Far::TopologyRefiner> refiner;
  {
    std::lock_guard lock(callbackMutex);
    tlsOsdErrors.clear();
    Far::SetErrorCallback(collectOsdError);
    refiner.reset(Factory::Create(desc, options));
    Far::SetErrorCallback(nullptr);
  }
  if (!refiner)
    throw Error(mesh.source + ": OpenSubdiv could not build the topology" +
                (tlsOsdErrors.empty() ? std::string() : ": " + tlsOsdErrors));
  return refiner;
}

TopologySummary summarize(const Far::TopologyRefiner& refiner) {
  const Far::TopologyLevel& level = refiner.GetLevel(0);
  TopologySummary s;
  s.vertices = level.GetNumVertices();
  s.faces = level.GetNumFaces();
  s.edges = level.GetNumEdges();
  for (int f = 0; f < s.faces; ++f) {
    const auto fv = level.GetFaceVertices(f);
    const int n = fv.size();
    if (n == 4)
      ++s.quads;
    else if (n == 3)
      ++s.triangles;
    else
      ++s.otherFaces;
    if (level.IsFaceHole(f)) ++s.holes;
    std::vector<int> sorted(fv.begin(), fv.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) ++s.degenerateFaces;
  }
  for (int e = 0; e < s.edges; ++e) {
    if (level.IsEdgeNonManifold(e))
      ++s.nonManifoldEdges;
    else if (level.GetEdgeFaces(e).size() == 1)
      ++s.boundaryEdges;
    // OpenSubdiv makes boundary and non-manifold edges infinitely sharp; count only the
    // interior edges that a tag made sharp.
    else if (level.GetEdgeSharpness(e) > 0.0f)
      ++s.creasedEdges;
  }
  for (int v = 0; v < s.vertices; ++v) {
    if (level.IsVertexNonManifold(v)) ++s.nonManifoldVertices;
    if (level.GetVertexFaces(v).size() == 0) ++s.unusedVertices;
    if (level.GetVertexSharpness(v) > 0.0f) ++s.cornerVertices;
    s.maxValence = std::max(s.maxValence, static_cast<int>(level.GetVertexEdges(v).size()));
    if (level.GetVertexFaces(v).size() > 0 && !level.IsVertexValenceRegular(v))
      ++s.extraordinaryVertices;
  }
  s.closed = s.boundaryEdges == 0 && s.nonManifoldEdges == 0 && s.holes == 0 && s.faces > 0;
  return s;
}

}  // namespace osd_cull
