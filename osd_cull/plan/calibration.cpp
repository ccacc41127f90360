#include "osd_cull/plan/calibration.h"

#include "osd_cull/error.h"
#include "osd_cull/hash.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace osd_cull::plan {
namespace {

namespace fs = std::filesystem;

// Format 3: per-method bounds passes ("bounds-method"), the displaced kernels ("cull
// con-caf ...") and the displaced draw ("draw-displaced"). Format 4: the back-patch
// accuracies ("cull-surface METHOD MS", "cull-listed METHOD LEVEL MS"). Format 5: the tight
// Hi-Z lookup ("hiz-tight MS"), a full-resolution Hi-Z build among the "hiz" sizes and the
// displaced bounds passes ("bounds-method acon|con MS"). Format 6: the listed test per
// patch it runs on. Format 7: a closing "end" line, so that a file cut at a line boundary
// is refused, not read as a calibration with fewer measurements. Older files are measured
// again.
constexpr const char* kMagicPrefix = "osd_cull-calibration ";
constexpr int kFormat = 7;
const std::string kMagic = kMagicPrefix + std::to_string(kFormat);

// The format of a calibration file's first line; 0 when it is not one.
int formatOf(const std::string& firstLine) {
  if (firstLine.rfind(kMagicPrefix, 0) != 0) return 0;
  return std::atoi(firstLine.c_str() + std::string(kMagicPrefix).size());
}

// The largest time a calibration field may hold, in ms: 10 s for one patch, submission or
// Hi-Z build is no measurement of a working device (a damaged or hand-edited file), and
// would make every prediction meaningless ("predicted inf ms").
constexpr double kMaxMs = 1e4;
// The largest ratio (gregory-draw-factor, draw-displaced) and TES invocations per patch
// ((64 + 1)² at the highest level, with margin).
constexpr double kMaxFactor = 1e3;
constexpr double kMaxInvocations = 1e5;

// The entries every calibration has, once each, and what they hold (for the errors).
const std::map<std::string, std::string>& requiredEntries() {
  static const std::map<std::string, std::string> entries = {
      {"device", "the device name"},
      {"driver", "the driver"},
      {"library", "the library version"},
      {"quick", "whether it is a quick calibration"},
      {"repeats", "the repeats behind each median"},
      {"patches", "the patches of the calibration mesh"},
      {"gregory-draw-factor", "the Gregory draw factor"},
      {"draw-zero", "RT0, ms per patch"},
      {"submit", "one submission, ms"},
      {"cull-dispatch", "the fixed cost of a cull dispatch, ms"},
      {"point-update-cpu", "the CPU point update, ms per patch"},
      {"point-update-gpu", "the GPU point update, ms per patch"},
      {"bounds", "the bounds pass, ms per patch"},
      {"end", "the closing line (a file without it was cut short)"}};
  return entries;
}

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// Linear interpolation of y over x through sorted samples; beyond the ends the nearest
// segment's line (or, with one sample, y proportional to x).
double interpolate(const std::vector<std::pair<double, double>>& s, double x) {
  if (s.size() == 1) return s[0].first > 0 ? s[0].second * x / s[0].first : s[0].second;
  size_t i = 1;
  while (i + 1 < s.size() && s[i].first < x) ++i;
  const auto [x0, y0] = s[i - 1];
  const auto [x1, y1] = s[i];
  const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 0.0;
  return std::max(0.0, y0 + t * (y1 - y0));
}

}  // namespace

namespace {

double drawCost(const std::vector<DrawCost>& draw, double tess, double DrawCost::*cost) {
  if (draw.empty()) throw Error("calibration: no draw costs RT(tf) measured");
  std::vector<std::pair<double, double>> s;
  for (const DrawCost& d : draw) s.push_back({(d.tess + 1.0) * (d.tess + 1.0), d.*cost});
  return interpolate(s, (tess + 1.0) * (tess + 1.0));
}

}  // namespace

double Calibration::drawMs(double tess) const {
  return drawCost(draw, tess, &DrawCost::msPerPatch);
}

double Calibration::backDrawMs(double tess) const {
  return drawCost(draw, tess, &DrawCost::backMsPerPatch);
}

double Calibration::displacedDrawFactorAt(double tess) const {
  if (displacedDrawFactor.empty()) return 1.0;
  const auto square = [](double t) { return (t + 1.0) * (t + 1.0); };
  if (tess <= displacedDrawFactor.front().first) return displacedDrawFactor.front().second;
  if (tess >= displacedDrawFactor.back().first) return displacedDrawFactor.back().second;
  std::vector<std::pair<double, double>> s;
  for (const auto& [level, factor] : displacedDrawFactor) s.push_back({square(level), factor});
  return interpolate(s, square(tess));
}

double Calibration::boundsMs(const std::string& method) const {
  for (const std::string& name :
       {method, method.substr(0, method.find("-16")), method.substr(0, method.find("-fp64"))})
    if (const auto it = boundsMsPerMethod.find(name); it != boundsMsPerMethod.end())
      return it->second;
  return boundsMsPerPatch;
}

double Calibration::listedCullMs(const std::string& method, double tess) const {
  const auto it = listedCullMsPerPatch.find(method);
  if (it == listedCullMsPerPatch.end() || it->second.empty())
    throw Error("calibration: no listed-triangle cost measured for back-patch method '" + method +
                "' (run `osd-cull calibrate --force` with this library)");
  std::vector<std::pair<double, double>> s;
  for (const auto& [level, ms] : it->second) s.push_back({(level + 1.0) * (level + 1.0), ms});
  return interpolate(s, (tess + 1.0) * (tess + 1.0));
}

double Calibration::cullMs(const std::string& stage) const {
  const auto it = cullMsPerPatch.find(stage);
  if (it == cullMsPerPatch.end())
    throw Error("calibration: no cull cost measured for stage '" + stage +
                "' (run `osd-cull calibrate` again with this library)");
  return it->second;
}

double Calibration::hizBuildMs(uint64_t pixels) const {
  if (hizBuild.empty()) throw Error("calibration: no Hi-Z build cost measured");
  std::vector<std::pair<double, double>> s;
  for (const SizeCost& c : hizBuild) s.push_back({double(c.pixels), c.ms});
  return interpolate(s, double(pixels));
}

std::string toText(const Calibration& c) {
  std::ostringstream out;
  out << kMagic << "\n";
  out << "device " << c.key.device << "\n";
  out << "driver " << c.key.driver << "\n";
  out << "library " << c.key.library << "\n";
  out << "quick " << (c.quick ? 1 : 0) << "\n";
  out << "repeats " << c.repeats << "\n";
  out << "patches " << c.patches << "\n";
  for (const DrawCost& d : c.draw)
    out << "draw " << d.tess << " " << number(d.msPerPatch) << " " << number(d.tesPerPatch) << " "
        << number(d.backMsPerPatch) << "\n";
  out << "gregory-draw-factor " << number(c.gregoryDrawFactor) << "\n";
  out << "draw-zero " << number(c.drawZeroMsPerPatch) << "\n";
  out << "submit " << number(c.submitMs) << "\n";
  out << "cull-dispatch " << number(c.cullDispatchMs) << "\n";
  for (const auto& [stage, ms] : c.cullMsPerPatch)
    out << "cull " << stage << " " << number(ms) << "\n";
  for (const SizeCost& h : c.hizBuild) out << "hiz " << h.pixels << " " << number(h.ms) << "\n";
  out << "point-update-cpu " << number(c.pointUpdateCpuMsPerPatch) << "\n";
  out << "point-update-gpu " << number(c.pointUpdateGpuMsPerPatch) << "\n";
  out << "bounds " << number(c.boundsMsPerPatch) << "\n";
  for (const auto& [level, factor] : c.displacedDrawFactor)
    out << "draw-displaced " << level << " " << number(factor) << "\n";
  for (const auto& [method, ms] : c.boundsMsPerMethod)
    out << "bounds-method " << method << " " << number(ms) << "\n";
  if (c.hizTightMsPerPatch) out << "hiz-tight " << number(*c.hizTightMsPerPatch) << "\n";
  for (const auto& [method, ms] : c.surfaceCullMsPerPatch)
    out << "cull-surface " << method << " " << number(ms) << "\n";
  for (const auto& [method, levels] : c.listedCullMsPerPatch)
    for (const auto& [level, ms] : levels)
      out << "cull-listed " << method << " " << level << " " << number(ms) << "\n";
  out << "end\n";
  return out.str();
}

namespace {

/// \brief One line of a calibration file, `NAME VALUES...`, and the readers of its values,
/// whose errors name the file, the line and the entry.
class EntryLine {
 public:
  EntryLine(const std::string& line, const std::string& source, int lineNumber)
      : source_(source), lineNumber_(lineNumber) {
    const size_t space = line.find(' ');
    name_ = line.substr(0, space);
    rest_ = space == std::string::npos ? "" : line.substr(space + 1);
    values_.str(rest_);
  }

  const std::string& name() const { return name_; }
  const std::string& rest() const { return rest_; }

  /// \brief The error `what` at this line.
  Error fail(const std::string& what) const {
    return Error(source_ + ":" + std::to_string(lineNumber_) + ": " + what);
  }

  /// \brief The next value into `v`, in [lo, hi] when a number: finite, and not beyond what a
  /// device measures.
  template <typename T>
  void read(T& v, const char* what, double lo = 0.0, double hi = kMaxMs) {
    std::string token;
    if (!(values_ >> token)) throw fail("'" + name_ + "' needs " + what + ", got '" + rest_ + "'");
    if constexpr (std::is_same_v<T, std::string>) {
      v = token;
    } else {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (token.empty() || *end != '\0' || (std::is_integral_v<T> && x != std::floor(x)))
        throw fail("'" + name_ + "' needs " + what + ", got '" + rest_ + "'");
      if (!std::isfinite(x) || x < lo || x > hi)
        throw fail("'" + name_ + "': " + what + " " + token + " is out of range [" + number(lo) +
                   ", " + number(hi) + "]");
      v = static_cast<T>(x);
    }
  }

  /// \brief `NAME ms-per-patch` into a map.
  void readNamed(std::map<std::string, double>& into, const char* what) {
    std::string key;
    double ms = 0;
    read(key, what);
    read(ms, "ms per patch");
    into[key] = ms;
  }

  /// \brief `KEY VALUE` appended to `into`, whose keys must ascend.
  template <typename List, typename Key, typename Value>
  void readAscending(List& into, Key key, Value value, const char* keyWhat, const char* valueWhat,
                     const char* keys, double keyMax, double valueMax = kMaxMs) {
    typename List::value_type entry{};
    read(entry.*key, keyWhat, 0, keyMax);
    read(entry.*value, valueWhat, 0, valueMax);
    if (!into.empty() && entry.*key <= into.back().*key)
      throw fail("'" + name_ + "' " + keys + " must ascend");
    into.push_back(entry);
  }

 private:
  const std::string& source_;
  int lineNumber_;
  std::string name_, rest_;
  std::istringstream values_;
};

/// \brief One `draw LEVEL MS TES BACK-MS` line appended to c.draw, whose levels must ascend.
void readDrawLine(EntryLine& e, Calibration& c) {
  DrawCost d;
  e.read(d.tess, "a tessellation level", 1, 64);
  e.read(d.msPerPatch, "ms per patch");
  e.read(d.tesPerPatch, "TES invocations per patch", 0, kMaxInvocations);
  e.read(d.backMsPerPatch, "ms per back-facing patch");
  if (!c.draw.empty() && d.tess <= c.draw.back().tess) throw e.fail("'draw' levels must ascend");
  c.draw.push_back(d);
}

/// \brief Reads one entry other than `end` into `c`; an unknown name is an error.
void readEntry(EntryLine& e, Calibration& c) {
  using LevelValue = std::pair<uint32_t, double>;
  const std::string& name = e.name();
  if (name == "device")
    c.key.device = e.rest();
  else if (name == "driver")
    c.key.driver = e.rest();
  else if (name == "library")
    c.key.library = e.rest();
  else if (name == "quick") {
    int q = 0;
    e.read(q, "0 or 1", 0, 1);
    c.quick = q != 0;
  } else if (name == "repeats")
    e.read(c.repeats, "a count", 1, 1e6);
  else if (name == "patches")
    e.read(c.patches, "a count", 1, 1e9);
  else if (name == "draw")
    readDrawLine(e, c);
  else if (name == "gregory-draw-factor")
    e.read(c.gregoryDrawFactor, "a factor", 0, kMaxFactor);
  else if (name == "draw-zero")
    e.read(c.drawZeroMsPerPatch, "ms per patch");
  else if (name == "submit")
    e.read(c.submitMs, "ms");
  else if (name == "cull-dispatch")
    e.read(c.cullDispatchMs, "ms");
  else if (name == "cull")
    e.readNamed(c.cullMsPerPatch, "a stage name");
  else if (name == "hiz")
    e.readAscending(c.hizBuild, &SizeCost::pixels, &SizeCost::ms, "a pixel count", "ms", "sizes",
                    1e12);
  else if (name == "point-update-cpu")
    e.read(c.pointUpdateCpuMsPerPatch, "ms per patch");
  else if (name == "point-update-gpu")
    e.read(c.pointUpdateGpuMsPerPatch, "ms per patch");
  else if (name == "bounds")
    e.read(c.boundsMsPerPatch, "ms per patch");
  else if (name == "draw-displaced")
    e.readAscending(c.displacedDrawFactor, &LevelValue::first, &LevelValue::second,
                    "a tessellation level", "a factor", "levels", 64, kMaxFactor);
  else if (name == "bounds-method")
    e.readNamed(c.boundsMsPerMethod, "a back-patch method name");
  else if (name == "hiz-tight") {
    double ms = 0;
    e.read(ms, "ms per patch");
    c.hizTightMsPerPatch = ms;
  } else if (name == "cull-surface")
    e.readNamed(c.surfaceCullMsPerPatch, "a back-patch method name");
  else if (name == "cull-listed") {
    std::string method;
    e.read(method, "a back-patch method name");
    e.readAscending(c.listedCullMsPerPatch[method], &LevelValue::first, &LevelValue::second,
                    "a tessellation level", "ms per patch", "levels of one method", 64);
  } else
    throw e.fail("unknown entry '" + name + "'");
}

/// \brief Refuses a calibration read whole that misses an entry, by name: a file cut short
/// (no closing `end` after `lastLine`) or missing a measurement.
void checkComplete(const Calibration& c, const std::set<std::string>& seen, bool ended,
                   int lastLine, const std::string& source) {
  for (const auto& [entry, what] : requiredEntries())
    if (!seen.count(entry))
      throw Error(source + ": no '" + entry + "' line (" + what + ")" +
                  (ended ? ""
                         : "; the file ends at line " + std::to_string(lastLine) +
                               " without its closing 'end' line: cut short?"));
  if (c.draw.empty()) throw Error(source + ": no 'draw' lines (RT(tf))");
  if (c.hizBuild.empty()) throw Error(source + ": no 'hiz' lines (the Hi-Z build)");
  if (!c.cullMsPerPatch.count("frustum"))
    throw Error(source + ": no 'cull frustum' line (the cull kernel's cost)");
}

}  // namespace

Calibration fromText(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kMagic) {
    if (const int format = formatOf(line); format > 0)
      throw Error(source + ":1: " + outdatedCalibrationMessage(format));
    throw Error(source + ":1: not a calibration file (expected first line '" + kMagic + "')");
  }
  int lineNumber = 1;
  Calibration c;
  std::set<std::string> seen;  // of requiredEntries()
  bool ended = false;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (line.empty()) continue;
    EntryLine entry(line, source, lineNumber);
    const std::string& name = entry.name();
    if (ended) throw entry.fail("'" + name + "' after the closing 'end' line");
    if (requiredEntries().count(name) && !seen.insert(name).second)
      throw entry.fail("'" + name + "' given twice");
    if (name == "end") {
      if (!entry.rest().empty())
        throw entry.fail("'end' takes no value, got '" + entry.rest() + "'");
      ended = true;
    } else {
      readEntry(entry, c);
    }
  }
  // Validated whole: a file cut short, or missing a measurement, is refused by name.
  checkComplete(c, seen, ended, lineNumber, source);
  return c;
}

fs::path calibrationCacheDirectory() {
  if (const char* dir = std::getenv("OSD_CULL_CALIBRATION_CACHE"); dir && *dir)
    return std::string(dir) == "off" ? fs::path() : fs::path(dir);
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "osd_cull" / "calibration";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "osd_cull" / "calibration";
  return {};
}

fs::path calibrationCacheFile(const CalibrationKey& key) {
  const fs::path dir = calibrationCacheDirectory();
  if (dir.empty()) return {};
  char name[64];
  std::snprintf(name, sizeof name, "%016llx.txt",
                static_cast<unsigned long long>(
                    fnv1a64(key.device + "\n" + key.driver + "\n" + key.library)));
  return dir / name;
}

Calibration loadCalibration(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot read the calibration file");
  std::ostringstream text;
  text << in.rdbuf();
  return fromText(text.str(), file.string());
}

std::string outdatedCalibrationMessage(int format) {
  return "calibration file format " + std::to_string(format) + ", this library reads format " +
         std::to_string(kFormat) +
         " (per-method bounds passes, displaced kernels and draw, back-patch accuracies, Hi-Z "
         "variants, displaced bounds passes, a closing 'end' line): measure "
         "it again with "
         "`osd-cull calibrate --force`";
}

std::optional<Calibration> loadCachedCalibration(const CalibrationKey& key, std::string* outdated) {
  const fs::path file = calibrationCacheFile(key);
  if (file.empty() || !fs::exists(file)) return std::nullopt;
  if (outdated) {
    std::ifstream in(file, std::ios::binary);
    std::string first;
    std::getline(in, first);
    if (const int format = formatOf(first); format > 0 && format != kFormat) {
      *outdated = file.string() + ": " + outdatedCalibrationMessage(format);
      return std::nullopt;
    }
  }
  if (!outdated) {
    Calibration c = loadCalibration(file);
    if (!(c.key == key)) return std::nullopt;
    return c;
  }
  // A damaged file (cut short, a value out of range) is measured again like an old one.
  try {
    Calibration c = loadCalibration(file);
    if (!(c.key == key)) return std::nullopt;
    return c;
  } catch (const Error& e) {
    *outdated = std::string(e.what()) + " (a damaged calibration file)";
    return std::nullopt;
  }
}

void storeCalibration(const Calibration& calibration, const fs::path& file) {
  std::error_code ec;
  if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
  const fs::path temporary = file.string() + ".tmp" + std::to_string(std::rand());
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!(out << toText(calibration)))
      throw Error(file.string() + ": cannot write the calibration file");
  }
  fs::rename(temporary, file, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw Error(file.string() + ": cannot write the calibration file (" + ec.message() + ")");
  }
}

}  // namespace osd_cull::plan
