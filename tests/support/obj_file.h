#pragma once
/// \file obj_file.h
/// \brief A cage written as an OBJ file (positions and faces), for tests that hand the
/// program a mesh of their own making.

#include "osd_cull/patch/cage_mesh.h"

#include <filesystem>

namespace osd_cull::test {

/// \brief Writes the positions (at full double precision, so that a mesh moved far from the
/// origin keeps its shape) and faces of `cage` to `file`; no tags, no texture coordinates.
void writeObj(const CageMesh& cage, const std::filesystem::path& file);

}  // namespace osd_cull::test
