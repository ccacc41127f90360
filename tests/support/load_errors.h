#pragma once
/// \file load_errors.h
/// \brief Checks of the errors the mesh loaders (adapters/) give for bad files.

#include <filesystem>
#include <initializer_list>
#include <string>

namespace osd_cull::test {

/// \brief Loads `file` (a cage, or patches for .bpt) and returns the error message; fails
/// the test if there is no osd_cull::Error.
std::string loadError(const std::filesystem::path& file);

/// \brief The load error of `file` starts with the file name (and ":LINE:" when `line` > 0)
/// and contains every phrase.
void expectLoadError(const std::filesystem::path& file, int line,
                     std::initializer_list<const char*> phrases);

}  // namespace osd_cull::test
