#pragma once
/// \file run_command.h
/// \brief Runs a program (the osd-cull CLI) from a test and captures what it prints.

#include <filesystem>
#include <string>

namespace osd_cull::test {

/// \brief Exit status (as from pclose/system) and stdout+stderr of a command.
struct CommandResult {
  int status = -1;
  std::string output;
  int exitCode() const;  ///< WEXITSTATUS, or -1 when it did not exit normally
};

/// \brief Runs `command` through the shell with stderr merged into stdout.
CommandResult runCommand(const std::string& command);

/// \brief Path of the built osd-cull program.
std::filesystem::path osdCullProgram();

}  // namespace osd_cull::test
