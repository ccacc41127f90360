#include "device_options.h"

namespace osd_cull::cli {

void addDeviceOptions(CLI::App& app, vulkan::ContextOptions& options) {
  app.add_option("--device", options.device,
                 "Vulkan device: index or name substring (default $OSD_CULL_DEVICE,\n"
                 "else the first discrete GPU, then integrated, then virtual, then CPU\n"
                 "(e.g. lavapipe))")
      ->type_name("X");
  app.add_flag("--validate", options.validation, "enable the Vulkan validation layers");
}

}  // namespace osd_cull::cli
