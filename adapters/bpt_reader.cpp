// BPT Bézier patch files → PatchSet (see load_mesh.h for the format).
#include "adapters/coordinate_limit.h"
#include "adapters/load_mesh.h"
#include "adapters/text_input.h"

#include <climits>
#include <cmath>

namespace osd_cull::adapters {
namespace {

// The line "3 3" that starts a patch. Other degrees ("2 2", "3 1") are a valid BPT file of
// patches we do not draw; anything else is a malformed line.
void checkDegrees(const std::vector<std::string_view>& tokens, const detail::LineReader& at,
                  const std::string& which) {
  if (tokens.size() == 2 && tokens[0] == "3" && tokens[1] == "3") return;
  const auto u = tokens.size() == 2 ? detail::parseInt(tokens[0]) : std::nullopt;
  const auto v = tokens.size() == 2 ? detail::parseInt(tokens[1]) : std::nullopt;
  if (u && v && *u > 0 && *v > 0)
    at.fail(which + " has degrees " + std::to_string(*u) + " " + std::to_string(*v) +
            ": unsupported degrees; only bicubic patches (degrees '3 3') are supported");
  at.fail("expected the degrees '3 3' that start " + which + ", found " + detail::quote(at.line()));
}

}  // namespace

PatchSet loadBezierPatches(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string bytes = detail::readFileBytes(path);
  detail::LineReader lines(bytes, file, /*joinContinuations=*/false);
  std::vector<std::string_view> tokens;
  auto nextContent = [&]() {
    while (lines.next()) {
      tokens = detail::splitTokens(lines.line());
      if (!tokens.empty() && tokens[0].front() != '#') return true;
    }
    return false;
  };

  if (!nextContent()) detail::fail(file, 0, "the file is empty; expected the patch count");
  const auto count = tokens.size() == 1 ? detail::parseInt(tokens[0]) : std::nullopt;
  if (!count)
    lines.fail("expected the patch count (one integer), found " + detail::quote(lines.line()));
  if (*count <= 0)
    lines.fail("the patch count is " + std::to_string(*count) + ": there are no patches");
  // Each patch takes 17 lines; a larger count is a wrong header or a truncated file and must
  // not become a huge allocation. Patches of other degrees take fewer lines: say so first.
  const auto left = static_cast<int64_t>(lines.remainingLines());
  {
    detail::LineReader ahead = lines;
    while (ahead.next()) {
      const auto first = detail::splitTokens(ahead.line());
      if (first.empty() || first[0].front() == '#') continue;
      checkDegrees(first, ahead, "patch 0");
      break;
    }
  }
  if (*count > left / 17)
    lines.fail("the file declares " + std::to_string(*count) +
               " patches (17 lines each) but only " + std::to_string(left) +
               " lines follow (truncated file or wrong count)");

  PatchSet set;
  set.source = file;
  set.bezierCount = static_cast<uint32_t>(*count);
  set.points.reserve(static_cast<size_t>(*count) * kBezierPoints);
  for (int64_t p = 0; p < *count; ++p) {
    const std::string which = "patch " + std::to_string(p) + " of " + std::to_string(*count);
    if (!nextContent())
      detail::fail(file, lines.lineNumber(), "the file ends before " + which + " (truncated)");
    checkDegrees(tokens, lines, which);
    for (uint32_t k = 0; k < kBezierPoints; ++k) {
      if (!nextContent())
        detail::fail(file, lines.lineNumber(),
                     "the file ends inside " + which + " after " + std::to_string(k) +
                         " of 16 points (truncated)");
      if (tokens.size() != 3)
        lines.fail("expected a point 'x y z' of " + which + ", found " +
                   detail::quote(lines.line()));
      double c[3];
      for (size_t i = 0; i < 3; ++i) {
        const auto value = detail::parseDouble(tokens[i]);
        if (!value) lines.fail("coordinate " + detail::quote(tokens[i]) + " is not a number");
        if (!std::isfinite(*value))
          lines.fail("point " + std::to_string(k) + " of " + which +
                     " has a NaN or Inf coordinate");
        if (auto problem = coordinateProblem(*value))
          lines.fail("point " + std::to_string(k) + " of " + which + ": coordinate " + *problem);
        c[i] = *value;
      }
      // The file lists four rows of four points with u fastest: PatchSet's order.
      set.points.emplace_back(c[0], c[1], c[2]);
    }
    OpenSubdiv::Far::PatchParam param;
    param.Set(static_cast<OpenSubdiv::Far::Index>(p), 0, 0, /*depth=*/0, /*nonquad=*/false,
              /*boundary=*/0,
              /*transition=*/0, /*regular=*/true);
    set.params.push_back(param);
    set.origins.push_back(PatchOrigin::Input);
  }
  if (nextContent())
    lines.fail("content after the last of " + std::to_string(*count) +
               " patches (is the count on the first line right?)");
  if (auto problem = extentProblem(set.points, "control points"))
    detail::fail(file, 0, *problem + ": scale the patches up");
  return set;
}

}  // namespace osd_cull::adapters
