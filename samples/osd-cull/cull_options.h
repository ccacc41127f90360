#pragma once
/// \file cull_options.h
/// \brief The culling options of osd-cull subcommands, parsed in one place: `--cull`,
/// `--backpatch-method` and the options of the two-pass occlusion frame.

#include "command.h"

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"

#include <optional>
#include <string>

namespace osd_cull::cli {

/// \brief Help text of the options below, for usage strings.
extern const char* const kCullOptionsUsage;

/// \brief What the user asked to cull.
struct CullChoice {
  std::string mode = "none";                      ///< none, frustum, backpatch, occlusion, all
  std::string backPatchMethod = "tangent-plane";  ///< a registered back-patch method
  /// Back-patch tests exact for the surface only (CullSettings::drawnTriangles = false).
  bool surfaceExact = false;
  /// The two-pass frame's options (used when occlusion() is true): aggressive, draw mode,
  /// first-frame policy, pyramid options.
  frame::CullFrameOptions frame;
  bool enabled() const { return mode != "none"; }
  /// \brief True when the Hi-Z occlusion stage runs (mode occlusion or all): frames are
  /// drawn by frame::CullFrame in two passes with temporal visibility.
  bool occlusion() const { return mode == "occlusion" || mode == "all"; }
};

/// \brief Reads `--cull MODE`, `--backpatch-method NAME`, `--surface-exact` and, for occlusion,
/// `--aggressive`,
/// `--draw-mode`, `--first-frame`, `--hiz-full`, `--hiz-tight`, `--hiz-reduction` (a command
/// using this lists aggressive, hiz-full and hiz-tight among its Command::flags).
/// \throws osd_cull::Error for unknown modes, methods or values, and for occlusion options
/// without an occlusion mode.
CullChoice cullChoiceFromArgs(Args& args);

/// \brief The cull-pass settings of a choice on a mesh with the given validity (back-patch
/// culling is left out with the reason where it is not valid).
frame::CullSettings cullSettings(const CullChoice& choice,
                                 const bound::BackPatchValidity& validity);

}  // namespace osd_cull::cli
