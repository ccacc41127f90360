#pragma once
/// \file obj_reader.h
/// \brief Wavefront OBJ with OpenSubdiv's tag lines → CageMesh (internal to adapters/).

#include "osd_cull/patch/cage_mesh.h"

#include <filesystem>
#include <string_view>

namespace osd_cull::adapters::detail {

/// \brief Parses OBJ text read from `path` (used for messages and to look for .mtl files).
/// `scheme` is already decided (option, file name or default); `leftHanded` reverses every
/// face's winding as OpenSubdiv's regression Shape does (first vertex kept).
/// \throws osd_cull::Error "FILE:LINE: problem" for anything that cannot be read.
CageMesh readObj(std::string_view text, const std::filesystem::path& path, Scheme scheme,
                 bool leftHanded);

}  // namespace osd_cull::adapters::detail
