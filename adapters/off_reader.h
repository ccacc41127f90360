#pragma once
/// \file off_reader.h
/// \brief ASCII OFF (Geomview Object File Format) → CageMesh (internal to adapters/).
///
/// OFF is read here rather than through OpenMesh because OpenMesh's OFF reader reports no
/// line numbers, trusts the header counts, and its mesh kernel refuses non-manifold faces
/// and faces that repeat a vertex; this reader keeps the face list exactly as written, so
/// OpenSubdiv sees what the file says. Binary OFF ("OFF BINARY") goes through OpenMesh.

#include "osd_cull/patch/cage_mesh.h"

#include <string>
#include <string_view>

namespace osd_cull::adapters::detail {

/// \brief True if the header keyword line of an OFF text says BINARY.
bool isBinaryOff(std::string_view text);

/// \brief Parses binary OFF: the line "[ST][C][N]OFF BINARY", then 32-bit integers and
/// floats: counts V F E, V × (x y z), and per face n, n indices, a colour count c and c
/// floats. The specification says big-endian; files in little-endian order (as OpenMesh
/// writes them) are recognised because their counts only fit the file size one way.
/// \throws osd_cull::Error "FILE: problem at byte OFFSET".
CageMesh readBinaryOff(std::string_view bytes, const std::string& file, Scheme scheme);

/// \brief Parses ASCII OFF: a header keyword ([ST][C][N]OFF), counts "V F E", V vertex lines
/// "x y z [extras]" and F face lines "n i0 ... i(n-1) [colour]" with 0-based indices;
/// '#' starts a comment. \throws osd_cull::Error "FILE:LINE: problem".
CageMesh readOff(std::string_view text, const std::string& file, Scheme scheme);

}  // namespace osd_cull::adapters::detail
