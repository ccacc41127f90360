#pragma once
/// \file cull_options.h
/// \brief The culling options of osd-cull subcommands, parsed in one place: `--cull` and
/// `--backpatch-method` (occlusion options are added here too).

#include "command.h"

#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/frame/cull_pass.h"

#include <optional>
#include <string>

namespace osd_cull::cli {

/// \brief Help text of the options below, for usage strings.
extern const char* const kCullOptionsUsage;

/// \brief What the user asked to cull.
struct CullChoice {
  std::string mode = "none";                      ///< none, frustum, backpatch, all
  std::string backPatchMethod = "tangent-plane";  ///< a registered back-patch method
  bool enabled() const { return mode != "none"; }
};

/// \brief Reads `--cull MODE` and `--backpatch-method NAME`.
/// \throws osd_cull::Error for unknown modes or methods.
CullChoice cullChoiceFromArgs(Args& args);

/// \brief The cull-pass settings of a choice on a mesh with the given validity (back-patch
/// culling is left out with the reason where it is not valid).
frame::CullSettings cullSettings(const CullChoice& choice,
                                 const bound::BackPatchValidity& validity);

}  // namespace osd_cull::cli
