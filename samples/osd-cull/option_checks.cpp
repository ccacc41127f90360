#include "option_checks.h"

#include "command.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace osd_cull::cli {

namespace fs = std::filesystem;

namespace {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string numberText(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// Creates and removes a file in `dir`: the one test of writability that also holds for
/// root and read-only file systems (access(2) answers from the permission bits only).
std::string writeProblem(const fs::path& dir) {
  const fs::path probe = dir / (".osd-cull-write-test-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return {};
}

}  // namespace

CLI::Validator integerIn(long lo, long hi) {
  return CLI::Validator(
      [lo, hi](std::string& v) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long x = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end != '\0' || errno == ERANGE) return "'" + v + "' is not an integer";
        if (x < lo || x > hi)
          return v + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        return {};
      },
      "");
}

CLI::Validator numberIn(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& v) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0' || !std::isfinite(x))
          return "'" + v + "' is not a finite number";
        if (x < lo || x > hi)
          return v + " is out of range [" + numberText(lo) + ", " + numberText(hi) + "]";
        return {};
      },
      "");
}

CLI::Validator oneOf(std::vector<std::string> choices, std::string what) {
  return CLI::Validator(
      [choices, what](std::string& v) -> std::string {
        if (std::find(choices.begin(), choices.end(), v) != choices.end()) return {};
        if (!what.empty()) return "'" + v + "' is not " + what + ": one of " + join(choices);
        return "'" + v + "' is not one of " + join(choices);
      },
      "");
}

CLI::Validator listOf(std::vector<std::string> choices) {
  return CLI::Validator(
      [choices](std::string& v) -> std::string {
        const auto items = splitList(v);
        if (items.empty() ||
            std::all_of(items.begin(), items.end(), [](const std::string& s) { return s.empty(); }))
          return "'" + v + "' names nothing; expected a comma-separated list of " + join(choices);
        for (const auto& item : items) {
          if (item.empty()) return "'" + v + "' has an empty item";
          if (std::find(choices.begin(), choices.end(), item) == choices.end())
            return "'" + item + "' is not one of " + join(choices);
        }
        return {};
      },
      "");
}

void addSizeOptions(CLI::App& app, std::optional<uint32_t>& width, std::optional<uint32_t>& height,
                    uint32_t minimum, const std::string& defaults) {
  addOptional(app, "--width", width, "width (default " + defaults + ")")
      ->type_name("W")
      ->check(integerIn(minimum, 16384));
  addOptional(app, "--height", height, "height (default " + defaults + ")")
      ->type_name("H")
      ->check(integerIn(minimum, 16384));
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    out.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

void checkOutputFile(const std::string& path, const std::string& option,
                     const std::vector<std::string>& extensions) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
    throw UsageError("option " + option + ": cannot write '" + path + "': the name must end in " +
                     join(extensions));
  if (fs::is_directory(path)) throw Error("option " + option + ": '" + path + "' is a directory");
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  if (!fs::is_directory(dir))
    throw Error("option " + option + ": directory '" + dir.string() + "' does not exist");
  if (const std::string problem = writeProblem(dir); !problem.empty())
    throw Error("option " + option + ": cannot write in directory '" + dir.string() +
                "': " + problem);
}

void prepareOutputDirectory(const std::string& dir, const std::string& option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("option " + option + ": '" + dir +
                "': cannot write there (cannot create the directory" +
                (ec ? ": " + ec.message() : "") + ")");
  if (const std::string problem = writeProblem(dir); !problem.empty())
    throw Error("option " + option + ": '" + dir + "': cannot write there (" + problem + ")");
}

}  // namespace osd_cull::cli
