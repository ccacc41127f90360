// osd-cull: command-line front end of osd_cull. `osd-cull --help` lists the subcommands.
#include "command.h"

#include "osd_cull/error.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>

namespace osd_cull::cli {

std::map<std::string, Command>& commands() {
  static std::map<std::string, Command> registry;
  return registry;
}

Registration::Registration(Command command) {
  std::string name = command.name;
  commands().emplace(std::move(name), std::move(command));
}

Args::Args(std::vector<std::string> argv, std::vector<std::string> flagNames) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() > 2 && a.starts_with("--")) {
      std::string name = a.substr(2);
      std::string val;
      bool hasInline = false;
      if (auto eq = name.find('='); eq != std::string::npos) {
        val = name.substr(eq + 1);
        name = name.substr(0, eq);
        hasInline = true;
      }
      bool isFlag = false;
      for (const auto& f : flagNames) isFlag |= (f == name);
      if (isFlag) {
        if (hasInline) throw Error("option --" + name + " takes no value");
        flags_[name] = true;
      } else if (hasInline) {
        values_[name] = val;
      } else {
        if (i + 1 >= argv.size()) throw Error("option --" + name + " needs a value");
        values_[name] = argv[++i];
      }
    } else {
      positional_.push_back(a);
    }
  }
}

std::optional<std::string> Args::value(const std::string& name) {
  used_[name] = true;
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::optional<long> Args::integer(const std::string& name, long lo, long hi) {
  auto v = value(name);
  if (!v) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long x = std::strtol(v->c_str(), &end, 10);
  if (v->empty() || *end != '\0' || errno == ERANGE)
    throw Error("option --" + name + ": '" + *v + "' is not an integer");
  if (x < lo || x > hi)
    throw Error("option --" + name + ": " + *v + " is out of range [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  return x;
}

std::optional<double> Args::number(const std::string& name, double lo, double hi) {
  auto v = value(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  if (v->empty() || *end != '\0' || !std::isfinite(x))
    throw Error("option --" + name + ": '" + *v + "' is not a finite number");
  if (x < lo || x > hi)
    throw Error("option --" + name + ": " + *v + " is out of range [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  return x;
}

bool Args::flag(const std::string& name) {
  used_[name] = true;
  return flags_.count(name) > 0;
}

void Args::finish() const {
  for (const auto& [name, _] : values_)
    if (!used_.count(name)) throw Error("unknown option --" + name);
  for (const auto& [name, _] : flags_)
    if (!used_.count(name)) throw Error("unknown option --" + name);
}

}  // namespace osd_cull::cli

namespace {

void printHelp() {
  std::cout << "osd-cull: GPU culling of OpenSubdiv patches\n\nUsage: osd-cull COMMAND "
               "[options]\n\nCommands:\n";
  for (const auto& [name, cmd] : osd_cull::cli::commands())
    std::cout << "  " << name << std::string(name.size() < 10 ? 10 - name.size() : 1, ' ')
              << cmd.summary << "\n";
  std::cout << "\n`osd-cull COMMAND --help` shows a command's options.\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace osd_cull::cli;
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    printHelp();
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  auto it = commands().find(name);
  if (it == commands().end()) {
    std::cerr << "osd-cull: unknown command '" << name << "'\n";
    printHelp();
    return 2;
  }
  std::vector<std::string> rest(argv + 2, argv + argc);
  for (const auto& a : rest)
    if (a == "--help" || a == "-h") {
      std::cout << it->second.usage;
      return 0;
    }
  try {
    Args args(std::move(rest), it->second.flags);
    return it->second.run(args);
  } catch (const std::exception& e) {
    std::cerr << "osd-cull " << name << ": error: " << e.what() << "\n";
    return 1;
  }
}
