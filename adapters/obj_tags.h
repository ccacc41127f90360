#pragma once
/// \file obj_tags.h
/// \brief OpenSubdiv's OBJ tag lines (`t NAME nint/nfloat/nstring args...`), internal to
/// adapters/. The meaning of each tag follows OpenSubdiv's regression harness
/// (regression/common/shape_utils.cpp parses, far_utils.h applies):
///
/// | tag | arguments | effect |
/// |---|---|---|
/// | crease | n ≥ 2 vertex indices, 1 or n-1 sharpnesses | sharp edges along the chain |
/// | corner | n ≥ 1 vertex indices, 1 or n sharpnesses | sharp vertices |
/// | hole | n ≥ 1 face indices | faces marked as holes |
/// | interpolateboundary | 1 int: 0 none, 1 edge-and-corner, 2 edge-only | boundary rule |
/// | facevaryinginterpolateboundary | 1 int: 0 none … 5 all (FVarLinearInterpolation) | |
/// | creasemethod | 1 string: normal (or uniform), chaikin | creasing method |
/// | smoothtriangles | 1 string: catmark, smooth (Catmull-Clark only) | triangle weights |
///
/// Tag indices are 0-based (unlike `f` lines). Sharpness below zero is clamped to zero,
/// as OpenSubdiv does. Unknown tag names are noted and ignored.

#include "osd_cull/patch/cage_mesh.h"
#include "text_input.h"  // relative: also resolves where the headers are installed

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace osd_cull::adapters::detail {

/// \brief Collects the tag lines of one OBJ file, then checks and applies them to the mesh.
class ObjTags {
 public:
  /// \brief Parses one tag line (tokens[0] == "t"). Throws through `at` on malformed input;
  /// appends to `notes` for ignored or adjusted input.
  void parse(const std::vector<std::string_view>& tokens, const LineReader& at, Scheme scheme,
             std::vector<std::string>& notes);

  /// \brief Checks every index against the finished mesh (vertices, faces, existing edges)
  /// and writes creases, corners, holes and options into it.
  /// \throws Error "FILE:LINE: problem" naming the tag line at fault.
  void apply(CageMesh& mesh, const std::string& file) const;

  /// \brief Appends notes for unknown tag names and clamped sharpness (call once at the end).
  void finishNotes(std::vector<std::string>& notes) const;

 private:
  struct Crease {
    int line;
    int64_t v0, v1;
    float sharpness;
  };
  struct Corner {
    int line;
    int64_t vertex;
    float sharpness;
  };
  struct Hole {
    int line;
    int64_t face;
  };

  /// Notes an option tag (interpolateboundary, creasemethod, ...) given again with another
  /// value.
  void noteRepeatedOption(const std::vector<std::string_view>& tokens, const LineReader& at,
                          std::vector<std::string>& notes);

  std::vector<Crease> creases_;
  std::vector<Corner> corners_;
  std::vector<Hole> holes_;
  std::optional<BoundaryInterpolation> boundary_;
  std::optional<FVarInterpolation> fvarBoundary_;
  std::optional<CreasingMethod> creasing_;
  std::optional<TriangleSubdivision> triangles_;
  int clampedSharpness_ = 0;
  int clampedSharpnessLine_ = 0;
  int extraArgs_ = 0;
  int extraArgsLine_ = 0;
  std::map<std::string, std::pair<int, std::string>> optionTags_;    ///< name → (line, value)
  std::map<std::string, std::pair<int, int>, std::less<>> unknown_;  ///< name → (count, first line)
};

}  // namespace osd_cull::adapters::detail
