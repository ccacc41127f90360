#pragma once
/// \file displacement_args.h
/// \brief The displacement options of `render` and `verify`: the map and the displaced
/// bounds (docs/user-guide.md, "Displacement").

#include "command.h"

#include "adapters/image_displacement.h"
#include "osd_cull/frame/cull/cull_methods.h"
#include "osd_cull/frame/draw/tess_levels.h"

#include <optional>
#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief The displacement options as given.
struct DisplacementArgs {
  std::string source;  ///< --displacement MAP|procedural; empty: no displacement
  std::optional<double> scale, midlevel;
  std::string channel;
  std::optional<uint32_t> lod;
  std::string bound, box;  ///< empty: acon, caf ("all" with verify)
  std::string tess;        ///< --displaced-tess edge|none|per-patch; empty: edge
};

/// \brief What the options chose.
struct DisplacementChoice {
  std::optional<adapters::DisplacementOptions> map;  ///< --displacement given
  /// --displaced-bound x --displaced-box ("all" expands): the kernels, in Table 1 order.
  std::vector<frame::CullMethod::Displaced> kernels;
  /// --displaced-tess: how adaptive levels account for the displacement.
  frame::DisplacedTessellation tessellation = frame::DisplacedTessellation::EdgeVariation;
};

/// \brief Declares --displacement, --displacement-scale, --displacement-midlevel,
/// --displacement-channel, --displacement-lod, --displaced-bound and --displaced-box.
/// `allowAll`: "all" is accepted for the bound and the box (verify).
void addDisplacementOptions(CLI::App& app, DisplacementArgs& args, bool allowAll);

/// \brief The choice the parsed options make. Defaults: acon, caf (verify: all with
/// --displaced-bound all).
/// \throws UsageError for displaced-bound options without --displacement, or a bad channel.
DisplacementChoice displacementChoice(const DisplacementArgs& args, bool allowAll);

/// \brief The kernels' method names ("acon-caf", ...).
std::vector<std::string> kernelNames(const DisplacementChoice& choice);

}  // namespace osd_cull::cli
