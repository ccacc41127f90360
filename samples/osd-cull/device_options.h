#pragma once
/// \file device_options.h
/// \brief `--device X` and `--validate`, the Vulkan options of osd-cull subcommands.

#include <CLI/CLI.hpp>

#include "osd_cull/vk/context.h"

namespace osd_cull::cli {

/// \brief Declares `--device X` (index or name substring) and `--validate` (validation
/// layers), filled into `options` when the line is parsed.
void addDeviceOptions(CLI::App& app, vulkan::ContextOptions& options);

}  // namespace osd_cull::cli
