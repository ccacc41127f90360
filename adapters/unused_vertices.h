#pragma once
/// \file unused_vertices.h
/// \brief Dropping the vertices no face uses, before refinement.

#include "osd_cull/patch/cage_mesh.h"

#include <cstddef>

namespace osd_cull::adapters {

/// \brief Removes the vertices no face uses and renumbers the rest (in order), so that
/// refinement, stencils and the cage → control-point matrix are sized by the surface, not
/// by the file: 25 M unused vertices around one triangle otherwise cost OpenSubdiv's
/// topology tables and stencils for every one of them (gigabytes, tens of seconds).
///
/// Face vertices, crease edges and corner tags are renumbered; a corner tag on an unused
/// vertex is dropped with it (it has no effect on the surface). Adds a note saying how many
/// were dropped. Positions an application supplies per frame must then be indexed the new
/// way: keep the cage as loaded when the file's vertex numbering matters.
/// \returns the number of vertices removed (0: the mesh is unchanged).
size_t dropUnusedVertices(CageMesh& mesh);

}  // namespace osd_cull::adapters
