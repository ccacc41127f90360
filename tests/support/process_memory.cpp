#include "support/process_memory.h"

#include <fstream>

#include <unistd.h>

namespace osd_cull::test {

uint64_t residentKb() {
  std::ifstream statm("/proc/self/statm");
  uint64_t size = 0, resident = 0;
  if (!(statm >> size >> resident)) return 0;
  return resident * (uint64_t(sysconf(_SC_PAGESIZE)) / 1024);
}

}  // namespace osd_cull::test
