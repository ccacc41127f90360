// osd-cull: command-line front end of osd_cull. `osd-cull --help` lists the subcommands.
// Parsing is CLI11's; each subcommand declares its options (command.h). Exit status: 0
// success, 1 bad input or a failed run, 2 a usage error (docs/user-guide.md).
#include "command.h"

#include "osd_cull/error.h"
#include "osd_cull/version.h"
#if OSD_CULL_HAVE_VIEWER
#include "viewer/view_state.h"
#endif

#include <opensubdiv/version.h>

#include <iostream>
#include <memory>
#include <sstream>
#include <string>

namespace osd_cull::cli {

std::map<std::string, Command>& commands() {
  static std::map<std::string, Command> registry;
  return registry;
}

Registration::Registration(Command command) {
  std::string name = command.name;
  commands().emplace(std::move(name), std::move(command));
}

}  // namespace osd_cull::cli

namespace {

using namespace osd_cull::cli;

/// CLI11's "The following argument was not expected: --x" as the guide words it.
std::string extrasMessage(const CLI::App& app, bool commandChosen) {
  for (const std::string& arg : app.remaining()) {
    if (arg.starts_with("-") && arg.size() > 1)
      return "unknown option " + arg.substr(0, arg.find('='));
    if (!commandChosen) return "unknown command '" + arg + "'";
    return "unexpected argument '" + arg + "'";
  }
  return "unexpected arguments";
}

/// Lists each command by its one-line summary (the first line of its description).
class Formatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    std::stringstream out;
    const std::string& d = sub->get_description();
    CLI::detail::format_help(out, sub->get_display_name(), d.substr(0, d.find('\n')),
                             column_width_);
    return out.str();
  }
};

std::string versionText() {
  return std::string("osd-cull ") + osd_cull::libraryVersion() + " (OpenSubdiv " +
         std::to_string(OPENSUBDIV_VERSION_MAJOR) + "." + std::to_string(OPENSUBDIV_VERSION_MINOR) +
         "." + std::to_string(OPENSUBDIV_VERSION_PATCH) + ")";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("osd-cull: GPU culling of OpenSubdiv patches", "osd-cull");
  app.require_subcommand(1);
  app.set_version_flag("--version", versionText(), "print the version and exit");
  app.footer("`osd-cull COMMAND --help` shows a command's options.");
  auto formatter = std::make_shared<Formatter>();
  formatter->column_width(28);
  app.formatter(formatter);
  std::map<const CLI::App*, Runner> runners;
  for (const auto& [name, command] : commands()) {
    CLI::App* sub = app.add_subcommand(name, command.summary);
    sub->description(command.summary + "\n\n" + command.description + "\n");
    if (!command.footer.empty()) sub->footer(command.footer);
    runners[sub] = command.setup(*sub);
  }
  const bool noArguments = argc < 2;
  CLI::App* chosen = nullptr;
  try {
    app.parse(argc, argv);
    chosen = app.get_subcommands().front();
    return runners.at(chosen)();
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion&) {
    std::cout << versionText() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    const auto subs = app.get_subcommands();
    const std::string prefix = subs.empty() ? "osd-cull" : "osd-cull " + subs.front()->get_name();
    if (noArguments) {
      std::cerr << app.help();
      return 2;
    }
    // An unknown command is not a subcommand CLI11 could require: it is left over.
    const bool extras = dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr ||
                        (subs.empty() && !app.remaining().empty());
    std::cerr << prefix << ": error: "
              << (extras ? extrasMessage(subs.empty() ? app : *subs.front(), !subs.empty())
                         : std::string(e.what()))
              << "\n"
              << "`" << prefix << " --help` lists the options.\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "osd-cull " << chosen->get_name() << ": error: " << e.what() << "\n";
    return 2;
#if OSD_CULL_HAVE_VIEWER
  } catch (const osd_cull::viewer::ScriptError& e) {  // a bad --script is a bad command line too
    std::cerr << "osd-cull " << chosen->get_name() << ": error: " << e.what() << "\n";
    return 2;
#endif
  } catch (const std::exception& e) {
    std::cerr << (chosen ? "osd-cull " + chosen->get_name() : std::string("osd-cull"))
              << ": error: " << e.what() << "\n";
    return 1;
  }
}
