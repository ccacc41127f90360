#pragma once
/// \file obj_sequence.h
/// \brief OBJ sequences (one OBJ per frame, identical topology) → scene::ObjSequence.
///
/// Defines osd_cull::scene::loadObjSequence (declared in osd_cull/scene/cage_animation.h,
/// implemented here because the library proper never parses files: link
/// osd_cull::adapters to use it) and the pattern expansion it uses.

#include "osd_cull/scene/cage_animation.h"

#include <filesystem>
#include <string>
#include <vector>

namespace osd_cull::adapters {

/// \brief The files of a sequence pattern, in frame order:
/// - `dir/frame_####.obj`: every run of '#' in the file name is one zero-padded frame
///   number of that many digits; the frames are the files of the folder that match, from
///   the smallest number found to the largest, which must all be there;
/// - `dir/name[0-58].obj` (RTXMG's range form): the frames first..last, written without
///   padding, or padded to the width of `first` when it has a leading zero ([00-58]).
/// \throws osd_cull::Error for a pattern with neither form, no matching file, or a
/// missing frame (naming the file that should be there).
std::vector<std::filesystem::path> expandSequencePattern(const std::string& pattern);

}  // namespace osd_cull::adapters
