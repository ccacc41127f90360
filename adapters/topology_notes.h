#pragma once
/// \file topology_notes.h
/// \brief Notes on unusual but legal topology, added to CageMesh::notes by every loader.
///
/// The loaders pass such faces to OpenSubdiv unchanged (it handles them); the notes only
/// tell the user what was found. osd_cull::summarize() gives OpenSubdiv's own counts.

#include "osd_cull/patch/cage_mesh.h"

namespace osd_cull::adapters {

/// \brief What noteTopology() found, by kind.
struct TopologyFindings {
  int facesRepeatingAVertex = 0;  ///< faces that use one vertex more than once
  int unusedVertices = 0;         ///< vertices no face uses
  int edgesWithManyFaces = 0;     ///< edges shared by more than two faces (non-manifold)
  int orientationConflicts = 0;   ///< two-face edges both faces traverse in the same direction
};

/// \brief Scans the face list of a valid cage (indices in range) and appends one note per
/// kind found, with the count and the first example. Returns the counts.
TopologyFindings noteTopology(CageMesh& mesh);

}  // namespace osd_cull::adapters
