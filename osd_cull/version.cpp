#include "osd_cull/version.h"

namespace osd_cull {

const char* libraryVersion() { return OSD_CULL_VERSION_STRING; }

}  // namespace osd_cull
