#include "support/run_command.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <memory>

namespace osd_cull::test {

int CommandResult::exitCode() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

CommandResult runCommand(const std::string& command) {
  CommandResult r;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  if (!pipe) return r;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe.get())) r.output += buffer.data();
  r.status = pclose(pipe.release());
  return r;
}

std::filesystem::path osdCullProgram() {
  return std::filesystem::path(OSD_CULL_BINARY_DIR) / "samples" / "osd-cull";
}

}  // namespace osd_cull::test
