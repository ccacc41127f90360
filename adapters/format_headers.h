#pragma once
/// \file format_headers.h
/// \brief Checks the headers of PLY and STL files against the file size before
/// a reader trusts them (internal to adapters/).
///
/// A header that claims more items than the remaining bytes can hold is a truncated file
/// or garbage; refusing it here keeps readers from allocating or looping on its counts.

#include <cstdint>
#include <string>
#include <string_view>

namespace osd_cull::adapters::detail {

/// \brief What a valid PLY header declares.
struct PlyHeader {
  bool ascii = true;
  int64_t vertices = 0;  ///< count of element "vertex"
  int64_t faces = 0;     ///< count of element "face"
};

/// \brief Parses and checks a PLY header: magic, format, elements and properties, a vertex
/// element with x, y, z, a face element with a list property, and counts that fit the
/// file. \throws osd_cull::Error "FILE:LINE: problem" (header lines are numbered).
PlyHeader checkPlyHeader(std::string_view bytes, const std::string& file);

/// \brief What an STL file looks like.
struct StlInfo {
  bool binary = false;
  int64_t triangles = 0;  ///< from the binary header, or the count of "facet" lines
};

/// \brief Classifies STL as binary (84-byte header, 50 bytes per triangle, size matching
/// exactly) or ASCII (starts with "solid"); checks binary coordinates are finite.
/// \throws osd_cull::Error naming the file when it is neither, or truncated.
StlInfo checkStl(std::string_view bytes, const std::string& file);

}  // namespace osd_cull::adapters::detail
