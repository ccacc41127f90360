#pragma once
/// \file test_scenes.h
/// \brief Scene files (JSON text) shared by the scene tests.

#include <string>

namespace osd_cull::test {

/// \brief A static displaced mesh (procedural map, con-oobb bound) beside a twisting
/// undisplaced one, one view, 2 frames at 80 x 64; the mesh file named absolutely in
/// dataDir().
std::string displacedScene();

}  // namespace osd_cull::test
