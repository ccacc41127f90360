#pragma once
/// \file scene_file.h
/// \brief Reads scene files (JSON, docs/scene-format.md) into scene::SceneDescription.
///
/// Strict: an unknown key, a value of the wrong type or range, an unknown mesh or parent
/// reference, a parent cycle, key frames whose times do not increase, or a field this
/// version does not support (displacement) is an osd_cull::Error whose message starts with
/// the file and the JSON pointer of the offending value, e.g.
/// `scene.json: /instances/2/transform: expected 16 numbers, got 12`.

#include "osd_cull/scene/scene_description.h"

#include <filesystem>
#include <string>

namespace osd_cull::adapters {

/// \brief Parses scene JSON text. Relative file names (meshes, sequences, occluders) are
/// resolved against `baseDir`; `source` names the text in errors.
/// \throws osd_cull::Error as described above.
scene::SceneDescription parseScene(const std::string& text, const std::string& source,
                                   const std::filesystem::path& baseDir);

/// \brief Reads and parses a scene file.
/// \throws osd_cull::Error when the file cannot be read, or as parseScene().
scene::SceneDescription loadSceneFile(const std::filesystem::path& path);

/// \brief Whether `path` names a scene file (extension .json).
bool isSceneFile(const std::filesystem::path& path);

}  // namespace osd_cull::adapters
