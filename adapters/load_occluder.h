#pragma once
/// \file load_occluder.h
/// \brief Triangle-mesh occluders (walls, terrain, props drawn as plain triangles before
/// the patches, Niessner & Loop §3) from OBJ files.

#include "osd_cull/frame/draw/triangle_mesh.h"

#include <filesystem>

namespace osd_cull::adapters {

/// \brief Reads the `v` and `f` lines of an OBJ file as triangles: every polygon is split
/// into a fan from its first vertex, faces tagged as holes are left out. No subdivision
/// rules apply, so the mesh may be open, non-manifold or inconsistently oriented.
/// \throws osd_cull::Error naming the file and line for anything that cannot be read, and
/// for files that are not .obj.
frame::TriangleMesh loadTriangleMesh(const std::filesystem::path& path);

}  // namespace osd_cull::adapters
