#pragma once
/// \file option_checks.h
/// \brief Validators for osd-cull options (integer and number ranges, choices, lists) and
/// the checks of output paths that run before any work starts.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::cli {

/// \brief An integer in [lo, hi]: "'two' is not an integer", "11 is out of range [0, 10]".
CLI::Validator integerIn(long lo, long hi);

/// \brief A finite number in [lo, hi].
CLI::Validator numberIn(double lo, double hi);

/// \brief One of `choices`: "'x' is not one of a, b, c", or with `what` ("a back-patch
/// method"): "'x' is not a back-patch method: one of a, b, c".
CLI::Validator oneOf(std::vector<std::string> choices, std::string what = {});

/// \brief A comma-separated list of at least one item, none empty, each one of `choices`.
CLI::Validator listOf(std::vector<std::string> choices);

/// \brief Declares option `name` whose value (checked by the validators the caller adds)
/// is stored in `target`; `target` stays empty when the option is not given, for options
/// whose default depends on other input (a scene's own image size, say).
template <class T>
CLI::Option* addOptional(CLI::App& app, const std::string& name, std::optional<T>& target,
                         const std::string& description) {
  return app.add_option_function<T>(
      name, [&target](const T& value) { target = value; }, description);
}

/// \brief Declares `--width W` and `--height H` (each in [minimum, 16384]) of an image or
/// window; `defaults` says what is used when they are not given ("640 x 480").
void addSizeOptions(CLI::App& app, std::optional<uint32_t>& width, std::optional<uint32_t>& height,
                    uint32_t minimum, const std::string& defaults);

/// \brief The items of a comma-separated list (empty items are kept, as empty strings).
std::vector<std::string> splitList(const std::string& text);

/// \brief Checks, before any work, that the file `path` given to `option` can be written:
/// its extension is one of `extensions` (lower case, with the dot; compared ignoring case),
/// it is not a directory, and its directory exists and is writable.
/// \throws UsageError for an extension we cannot write, osd_cull::Error for the directory.
void checkOutputFile(const std::string& path, const std::string& option,
                     const std::vector<std::string>& extensions);

/// \brief Creates the directory `dir` given to `option` if needed and checks that it is
/// writable, before any work. \throws osd_cull::Error naming the option and the directory.
void prepareOutputDirectory(const std::string& dir, const std::string& option);

}  // namespace osd_cull::cli
