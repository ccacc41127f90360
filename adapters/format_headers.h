#pragma once
/// \file format_headers.h
/// \brief Structural checks of PLY and STL files before OpenMesh's readers see them
/// (internal to adapters/).
///
/// OpenMesh's readers trust their input: its PLY reader loops on header counts and reads
/// uninitialised values once a token fails to parse (a PLY with "inf" or garbage after the
/// header made it spin for minutes), its ASCII STL reader takes whatever three lines follow
/// "outer loop" as corners and turns unparsable numbers into 0. These checks walk the file
/// exactly as the reader will, so a file that passes is read as written, and a file that
/// fails gets an error naming the line (ASCII) or byte offset (binary) and the problem.

#include <cstdint>
#include <string>
#include <string_view>

namespace osd_cull::adapters::detail {

/// \brief What a checked PLY file declares.
struct PlyInfo {
  bool ascii = true;
  int64_t vertices = 0;  ///< count of element "vertex"
  int64_t faces = 0;     ///< count of element "face"
  int64_t trailing = 0;  ///< lines (ASCII) or bytes (binary) after the last element
};

/// \brief Checks a whole PLY file: magic, format, elements and properties (a vertex element
/// with x, y, z; a face element with a vertex_indices list), counts that fit the file, and
/// every element: numbers that parse (finite coordinates), lists of at least three vertex
/// indices in range. \throws osd_cull::Error "FILE:LINE: problem" or "FILE: problem at
/// byte N".
PlyInfo checkPly(std::string_view bytes, const std::string& file);

/// \brief What a checked STL file looks like.
struct StlInfo {
  bool binary = false;
  int64_t triangles = 0;  ///< triangles in the file
};

/// \brief Classifies STL as binary (84-byte header, 50 bytes per triangle, size matching
/// exactly) or ASCII (starts with "solid") and checks it: finite coordinates; in ASCII,
/// facets of "outer loop", three "vertex x y z" lines and "endloop".
/// \throws osd_cull::Error naming the file (and line) when it is neither, or malformed.
StlInfo checkStl(std::string_view bytes, const std::string& file);

}  // namespace osd_cull::adapters::detail
