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

/// \brief What the user asked to cull.
struct CullChoice {
  std::string mode = "none";                      ///< none, frustum, backpatch, occlusion, all
  std::string backPatchMethod = "tangent-plane";  ///< a registered back-patch method
  /// --backpatch-method was given: with the plan, the one method it may choose.
  bool backPatchMethodGiven = false;
  /// Back-patch tests exact for the surface only (CullSettings::drawnTriangles = false).
  bool surfaceExact = false;
  /// Clusters tested first (CullSettings::clusters; static points).
  bool clusters = false;
  /// The two-pass frame's options (used when occlusion() is true): aggressive, draw mode,
  /// first-frame policy, pyramid options.
  frame::CullFrameOptions frame;
  bool enabled() const { return mode != "none"; }
  /// \brief True when the Hi-Z occlusion stage runs (mode occlusion or all): frames are
  /// drawn by frame::CullFrame in two passes with temporal visibility.
  bool occlusion() const { return mode == "occlusion" || mode == "all"; }
};

/// \brief The culling options as given on the command line (empty: not given).
struct CullArgs {
  std::string mode;             ///< empty: not given (none, unless a form has its own default)
  std::string backPatchMethod;  ///< empty: not given (tangent-plane)
  bool surfaceExact = false;
  bool clusters = false;
  bool aggressive = false;
  std::string drawMode;
  std::string firstFrame;
  bool hizFull = false;
  bool hizTight = false;
  std::string hizReduction;
};

/// \brief Declares `--cull MODE`, `--backpatch-method NAME`, `--surface-exact` and the
/// occlusion options `--aggressive`, `--draw-mode`, `--first-frame`, `--hiz-full`,
/// `--hiz-tight`, `--hiz-reduction` in a "Culling" group of `app`; unknown values are
/// parse errors that list the valid ones.
void addCullOptions(CLI::App& app, CullArgs& args);

/// \brief The choice the parsed options make.
/// \throws UsageError for options that need another one (occlusion options without an
/// occlusion mode, `--surface-exact` without back-patch culling).
CullChoice cullChoice(const CullArgs& args);

/// \brief The cull-pass settings of a choice on a mesh with the given validity (back-patch
/// culling is left out with the reason where it is not valid).
frame::CullSettings cullSettings(const CullChoice& choice,
                                 const bound::BackPatchValidity& validity);

}  // namespace osd_cull::cli
