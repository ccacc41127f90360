#pragma once
/// \file refiner.h
/// \brief CageMesh → OpenSubdiv Far::TopologyRefiner, and what the topology looks like.

#include "osd_cull/patch/cage_mesh.h"

#include <opensubdiv/far/topologyRefiner.h>

#include <memory>

namespace osd_cull {

namespace Far = OpenSubdiv::Far;

/// \brief Builds the base-level refiner of a cage with its scheme, boundary rule, creasing
/// method, triangle weights, creases, corners and holes. Validates the cage first.
/// \throws osd_cull::Error naming the mesh and OpenSubdiv's complaint when it refuses it.
std::unique_ptr<Far::TopologyRefiner> makeTopologyRefiner(const CageMesh& mesh);

/// \brief Facts about the base level of a refiner, as OpenSubdiv sees them.
struct TopologySummary {
  int vertices = 0;
  int faces = 0;
  int edges = 0;
  int quads = 0;           ///< faces with four vertices
  int triangles = 0;       ///< faces with three vertices
  int otherFaces = 0;      ///< faces with five or more vertices
  int holes = 0;
  int boundaryEdges = 0;   ///< edges with one incident face
  int nonManifoldEdges = 0;     ///< more than two faces, or orientation conflicts
  int nonManifoldVertices = 0;
  int unusedVertices = 0;  ///< vertices no face uses
  int degenerateFaces = 0; ///< faces that repeat a vertex
  int creasedEdges = 0;    ///< interior manifold edges with sharpness > 0 (tagged creases)
  int cornerVertices = 0;  ///< vertices with sharpness > 0
  int maxValence = 0;      ///< largest number of edges at a vertex
  int extraordinaryVertices = 0;
  /// No boundary edges, no non-manifold edges, no holes: the surface encloses a volume
  /// (a prerequisite of back-patch culling).
  bool closed = false;
};

/// \brief Reads the base level of a refiner.
TopologySummary summarize(const Far::TopologyRefiner& refiner);

}  // namespace osd_cull
