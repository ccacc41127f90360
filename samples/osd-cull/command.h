#pragma once
/// \file command.h
/// \brief Subcommand registry of the osd-cull program and its usage error.
///
/// A subcommand is one .cpp file with a static `osd_cull::cli::Registration`. Its `setup`
/// declares the command's options on a CLI11 `CLI::App` (bound to a struct the command
/// owns) and returns the function that runs it once the line is parsed. Option groups
/// shared by several commands (mesh, patches, culling, device) have an `add...Options`
/// function next to the struct they fill (mesh_source.h, cull_options.h,
/// device_options.h); option_checks.h has the validators (ranges, choices, lists) and the
/// output-path checks. CLI11 rejects unknown options, options declared twice and missing
/// values; main.cpp turns its errors into `osd-cull COMMAND: error: ...` and exit status 2.

#include "osd_cull/error.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>

namespace osd_cull::cli {

/// \brief A bad command line found after parsing (options that exclude each other, an
/// option that needs another one). Exits with status 2, like CLI11's parse errors; bad
/// input files and device failures are osd_cull::Error and exit with status 1.
class UsageError : public Error {
 public:
  using Error::Error;
};

/// \brief Runs a parsed command; returns the exit status.
using Runner = std::function<int()>;

/// \brief A subcommand: name, one-line summary, help text, and its option declarations.
struct Command {
  std::string name;
  std::string summary;      ///< one line, listed by `osd-cull --help`
  std::string description;  ///< paragraphs before the options in `osd-cull NAME --help`
  /// Declares the command's options and positionals on `app` and returns the function
  /// that runs the command with the parsed values.
  std::function<Runner(CLI::App& app)> setup;
  std::string footer = {};  ///< text after the options in `osd-cull NAME --help`
};

/// \brief Registers a subcommand at static-initialization time.
struct Registration {
  explicit Registration(Command command);
};

/// \brief All registered subcommands, by name.
std::map<std::string, Command>& commands();

}  // namespace osd_cull::cli
