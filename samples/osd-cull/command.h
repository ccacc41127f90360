#pragma once
/// \file command.h
/// \brief Subcommand registry and argument parsing of the osd-cull program.
///
/// A subcommand is one .cpp file with a static `osd_cull::cli::Registration`.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief Parsed command line of one subcommand: `--name value`, `--flag`, positionals.
/// Every option a command reads is marked used; unknown options are an error.
class Args {
 public:
  Args(std::vector<std::string> argv, std::vector<std::string> flagNames);

  /// Value of `--name V`, or nullopt.
  std::optional<std::string> value(const std::string& name);
  /// Value of `--name V` parsed as an integer in [lo, hi]; throws a clear error otherwise.
  std::optional<long> integer(const std::string& name, long lo, long hi);
  /// Value of `--name V` parsed as a finite number in [lo, hi].
  std::optional<double> number(const std::string& name, double lo, double hi);
  /// True when `--name` was given (a flag without value).
  bool flag(const std::string& name);
  /// Positional arguments in order.
  const std::vector<std::string>& positional() const { return positional_; }
  /// Throws if any option was given that no call above asked for.
  void finish() const;

 private:
  std::map<std::string, std::string> values_;
  std::map<std::string, bool> flags_;
  std::map<std::string, bool> used_;
  std::vector<std::string> positional_;
};

/// \brief A subcommand: name, one-line summary, usage text, and the function to run.
struct Command {
  std::string name;
  std::string summary;
  std::string usage;               ///< full help text, shown by `osd-cull NAME --help`
  std::vector<std::string> flags;  ///< options that take no value
  std::function<int(Args&)> run;
};

/// \brief Registers a subcommand at static-initialization time.
struct Registration {
  explicit Registration(Command command);
};

/// \brief All registered subcommands, by name.
std::map<std::string, Command>& commands();

}  // namespace osd_cull::cli
