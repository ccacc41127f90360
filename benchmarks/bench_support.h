#pragma once
/// \file bench_support.h
/// \brief Small helpers shared by the benchmarks: statistics, the command line (options,
/// --help, errors naming the option), the run wrapper of main(), progress lines and CSV
/// files. Header-only: every benchmarks/bench_*.cpp is a program of its own.

#include "adapters/load_mesh.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/draw/tess_levels.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/vk/context.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/resource.h>

namespace osd_cull::bench {

/// \brief The median (mean of the two middle values for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// \brief A comma-separated list of unsigned numbers ("4,8,16").
/// \throws std::invalid_argument or std::out_of_range for an item that is not a number.
inline std::vector<uint32_t> numberList(const std::string& text) {
  std::vector<uint32_t> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(static_cast<uint32_t>(std::stoul(item)));
  return out;
}

// The uniform levels, then the screen-space adaptive ones (label "aN": N pixels per
// segment, up to maxLevel), each with its label.
inline std::vector<std::pair<std::string, frame::TessellationOptions>> tessellationLevels(
    const std::vector<uint32_t>& uniform, const std::vector<uint32_t>& adaptive,
    uint32_t maxLevel) {
  std::vector<std::pair<std::string, frame::TessellationOptions>> levels;
  for (uint32_t tess : uniform) {
    frame::TessellationOptions t;
    t.uniformLevel = tess;
    levels.push_back({std::to_string(tess), t});
  }
  for (uint32_t pixels : adaptive) {
    frame::TessellationOptions t;
    t.mode = frame::TessellationOptions::Mode::Adaptive;
    t.pixelsPerSegment = pixels;
    t.maxLevel = maxLevel;
    levels.push_back({"a" + std::to_string(pixels), t});
  }
  return levels;
}

/// \brief A comma-separated list of names ("default,bigguy0").
inline std::vector<std::string> nameList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

/// \brief A benchmark's command line, on CLI11 (as the osd-cull program): options are
/// declared with the variable each one sets (its value before parse() is the default --help
/// shows), then parse() reads argv. A value out of its range is refused with the option's
/// name, never clamped.
class CommandLine {
 public:
  /// \brief `program` ("bench-draw") and `source` ("bench_draw.cpp", whose top comment
  /// describes the options) are named in --help and in errors.
  CommandLine(std::string program, std::string source)
      : app_(std::make_shared<CLI::App>("What the options do and what " + program +
                                            " prints: the comment at the top of "
                                            "benchmarks/" +
                                            source + ".",
                                        program)),
        source_(std::move(source)) {
    app_->option_defaults()->always_capture_default();
    app_->get_formatter()->column_width(36);
  }

  /// \brief `--name TEXT`.
  CommandLine& text(const std::string& name, std::string& value) {
    app_->add_option(name, value)->type_name("TEXT");
    return *this;
  }
  /// \brief `--name N`, a whole number of at least `atLeast`.
  CommandLine& number(const std::string& name, uint32_t& value, uint32_t atLeast = 0) {
    app_->add_option(name, value)
        ->type_name("N")
        ->check(CLI::Range(atLeast, std::numeric_limits<uint32_t>::max()));
    return *this;
  }
  /// \brief `--name N`, a signed whole number of at least `atLeast`.
  CommandLine& integer(const std::string& name, int& value, int atLeast) {
    app_->add_option(name, value)
        ->type_name("N")
        ->check(CLI::Range(atLeast, std::numeric_limits<int>::max()));
    return *this;
  }
  /// \brief `--name X`, a real number of at least `atLeast`.
  CommandLine& real(const std::string& name, double& value, double atLeast) {
    app_->add_option(name, value)
        ->type_name("X")
        ->check(CLI::Range(atLeast, std::numeric_limits<double>::max()));
    return *this;
  }
  /// \brief `--name N,N,...`.
  CommandLine& numbers(const std::string& name, std::vector<uint32_t>& values) {
    app_->add_option(name, values)->type_name("N,N,...")->delimiter(',');
    return *this;
  }
  /// \brief `--name A,B,...`.
  CommandLine& names(const std::string& name, std::vector<std::string>& values) {
    app_->add_option(name, values)->type_name("A,B,...")->delimiter(',');
    return *this;
  }
  /// \brief The options every Vulkan benchmark has: `--width N`, `--height N` (the image),
  /// `--repeats N` (at least 1) and `--device X` (vulkan::ContextOptions::device).
  CommandLine& imageAndDevice(uint32_t& width, uint32_t& height, uint32_t& repeats,
                              std::string& device) {
    return number("--width", width, 1)
        .number("--height", height, 1)
        .number("--repeats", repeats, 1)
        .text("--device", device);
  }
  /// \brief A positional argument (no option name), e.g. a mesh file.
  CommandLine& positional(const std::string& name, std::string& value) {
    app_->add_option(name, value)->type_name("FILE");
    return *this;
  }
  /// \brief `--name` without a value: sets `value`.
  CommandLine& flag(const std::string& name, bool& value) {
    app_->add_flag(name, value);
    return *this;
  }

  /// \brief Reads the options of argv into their variables. Returns false after printing
  /// the options for --help (or -h): the caller exits with 0.
  /// \throws osd_cull::Error naming the option ("--frames: Value 0 not in range ...",
  /// "unknown option --x (see the comment at the top of SOURCE)").
  bool parse(int argc, char** argv) const {
    try {
      app_->parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
      std::printf("%s", help().c_str());
      return false;
    } catch (const CLI::ExtrasError& e) {
      throw Error(std::string(e.what()) + " (see the comment at the top of " + source_ + ")");
    } catch (const CLI::ParseError& e) {
      throw Error(e.what());
    }
    return true;
  }

  /// \brief The usage line, one line an option with its default, and where the options
  /// are described.
  std::string help() const { return app_->help(); }

 private:
  // Shared: a CommandLine returned from a function that declares the options is a copy
  // of the chain. parse() is const; CLI11 records what it parsed.
  std::shared_ptr<CLI::App> app_;
  std::string source_;
};

/// \brief A benchmark's main(): the exit code of `body`, or 1 after "PROGRAM: message" on
/// stderr when it throws.
inline int run(const char* program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
}

/// \brief The options of the benchmark's Vulkan context: the device `--device` named
/// (empty: the default choice).
inline vulkan::ContextOptions contextOptions(const std::string& device) {
  vulkan::ContextOptions o;
  o.device = device;
  return o;
}

/// \brief "load average A B C, peak RSS N MiB": the three load averages of /proc/loadavg
/// ("?" where there is none) and this process's peak resident set, printed beside timings
/// measured on a shared machine.
inline std::string machineState() {
  std::string load = "?";
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    double a = 0, b = 0, c = 0;
    if (std::fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) {
      char text[64];
      std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
      load = text;
    }
    std::fclose(f);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);  // ru_maxrss in KiB on Linux
  return "load average " + load + ", peak RSS " + std::to_string(usage.ru_maxrss / 1024) + " MiB";
}

/// \brief A progress line on stderr: seconds since the first call, and what runs.
inline void progress(const std::string& what) {
  static const auto start = std::chrono::steady_clock::now();
  const std::chrono::duration<double> t = std::chrono::steady_clock::now() - start;
  std::fprintf(stderr, "[%7.1f s] %s\n", t.count(), what.c_str());
}

/// \brief A CSV file opened for writing with its `header` line written; null when `path`
/// is empty (no CSV asked for).
/// \throws osd_cull::Error "--csv: cannot write PATH".
using CsvFile = std::unique_ptr<FILE, int (*)(FILE*)>;
inline CsvFile openCsv(const std::string& path, const char* header) {
  CsvFile csv(nullptr, &std::fclose);
  if (path.empty()) return csv;
  csv.reset(std::fopen(path.c_str(), "w"));
  if (!csv) throw Error("--csv: cannot write " + path);
  std::fprintf(csv.get(), "%s\n", header);
  return csv;
}

/// \brief The data folder beside the project (as the tests find it), or $OSD_CULL_DATA_DIR.
inline std::filesystem::path dataDir() {
  if (const char* d = std::getenv("OSD_CULL_DATA_DIR")) return d;
  return std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data";
}

/// \brief Patches of a cage file at an isolation level, and whether back-patch culling (and
/// so rasterizer back-face culling) is valid on it: a closed, consistently oriented mesh.
struct CullMesh {
  PatchSet patches;
  bound::BackPatchValidity validity;
};

/// \brief Loads `path` and extracts its patches at isolation `level`.
inline CullMesh loadCullMesh(const std::filesystem::path& path, uint32_t level) {
  PatchOptions options;
  options.isolationLevel = static_cast<int>(level);
  bound::CullablePatches c = bound::cullablePatches(adapters::loadCage(path), options);
  return {std::move(c.extraction.patches), std::move(c.backPatch)};
}

}  // namespace osd_cull::bench
