#pragma once
/// \file openmesh_reader.h
/// \brief PLY and STL (ASCII and binary) through OpenMesh's readers (internal).
///
/// OpenMesh's readers parse the files; instead of OpenMesh's mesh kernel (which refuses
/// non-manifold faces and faces that repeat a vertex, and splits such faces off onto copied
/// vertices), a small importer records the vertex and face lists exactly as the reader
/// delivers them, so non-manifold input reaches OpenSubdiv unchanged. Before OpenMesh sees
/// a file, checkPly()/checkStl() (format_headers.h) walk it the way the reader will: a
/// header claiming 10^12 items, a truncated body, an unparsable number or an index out of
/// range is an error naming the line or byte, instead of an allocation, a hang or a
/// silently wrong mesh inside OpenMesh. STL corners are merged by OpenMesh's reader (equal
/// float positions become one vertex) and triangles that collapse are dropped (noted).

#include "osd_cull/patch/cage_mesh.h"

#include <filesystem>
#include <string_view>

namespace osd_cull::adapters::detail {

/// \brief True when this build reads PLY and STL (OpenMesh was found).
bool haveOpenMesh();

/// \brief Reads `path` (whose bytes are `bytes`) with OpenMesh; the format comes from the
/// extension (.ply, .stl). \throws osd_cull::Error naming the file and the problem.
CageMesh readWithOpenMesh(const std::filesystem::path& path, std::string_view bytes, Scheme scheme);

}  // namespace osd_cull::adapters::detail
