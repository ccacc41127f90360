#pragma once
/// \file displacement_args.h
/// \brief The displacement options of `render` and `verify`: the map and the displaced
/// bounds (docs/user-guide.md, "Displacement").

#include "command.h"

#include "adapters/image_displacement.h"
#include "osd_cull/frame/cull/cull_methods.h"

#include <optional>
#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief The options' help text (for both subcommands' usage).
extern const char* kDisplacementUsage;

/// \brief What the options chose.
struct DisplacementChoice {
  std::optional<adapters::DisplacementOptions> map;  ///< --displacement given
  /// --displaced-bound x --displaced-box ("all" expands): the kernels, in Table 1 order.
  std::vector<frame::CullMethod::Displaced> kernels;
};

/// \brief Reads --displacement, --displacement-scale, --displacement-midlevel,
/// --displacement-channel, --displacement-lod, --displaced-bound and --displaced-box.
/// `allowAll`: "all" is accepted (verify). Defaults: acon, caf.
/// \throws osd_cull::Error naming the option for bad values, or displaced-bound options
/// without --displacement.
DisplacementChoice displacementFromArgs(Args& args, bool allowAll);

/// \brief The kernels' method names ("acon-caf", ...).
std::vector<std::string> kernelNames(const DisplacementChoice& choice);

}  // namespace osd_cull::cli
