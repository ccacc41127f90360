#pragma once
/// \file calibration.h
/// \brief What the effect plan's cost model needs to know about a device, measured once by
/// `osd-cull calibrate` (measure/calibrate.h) and cached on disk, keyed by device, driver and
/// library version.
///
/// The figures are the terms of Niessner & Loop §6.3 (RT(tf): render time of a patch at
/// tessellation factor tf; RT0: of a patch drawn with factor 0; CT: cull time of a patch)
/// and of Zachmann's T = t + (1 - P)·R, per patch, in milliseconds, each a median over
/// repeats. This header is plain data and text I/O: no Vulkan.
///
/// Cache location: `$OSD_CULL_CALIBRATION_CACHE` (a directory; `off` disables it), else
/// `$XDG_CACHE_HOME/osd_cull/calibration`, else `$HOME/.cache/osd_cull/calibration`, as the
/// SPIR-V cache (vk/glsl/spirv_disk_cache.h).

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace osd_cull::plan {

/// \brief What a calibration belongs to: a calibration of another device, driver or
/// library version is not used.
struct CalibrationKey {
  std::string device;   ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string driver;   ///< e.g. "llvmpipe Mesa 22.3.6"
  std::string library;  ///< osd_cull::libraryVersion()
  bool operator==(const CalibrationKey&) const = default;
};

/// \brief RT(tf) at one level: per patch drawn, wall ms and tessellation-evaluation
/// invocations (pipeline statistics: exact work, (tf + 1)² for a uniform quad).
struct DrawCost {
  uint32_t tess = 1;
  double msPerPatch = 0.0;  ///< a closed mesh seen from outside (about half faces away)
  double tesPerPatch = 0.0;
  /// A patch whose triangles all face away (the rasterizer culls them): what culling a
  /// back-facing or off-screen patch saves; it is tessellated, never shaded.
  double backMsPerPatch = 0.0;
};

/// \brief A cost against a size (the Hi-Z build against the depth image's pixel count).
struct SizeCost {
  uint64_t pixels = 0;
  double ms = 0.0;
};

/// \brief The cull-stage names of Calibration::cullMsPerPatch: "frustum" and every
/// back-patch and occlusion method of frame::cullMethods() ("tcone", "hiz", "con-caf", ...).
/// A back-patch or occlusion stage's cost is what it adds to a kernel that runs the
/// frustum stage; the frustum's is the whole kernel's.

/// \brief One device's calibration.
struct Calibration {
  CalibrationKey key;
  bool quick = false;          ///< measured with `calibrate --quick` (fewer repeats, smaller sets)
  uint32_t repeats = 0;        ///< repeats behind each median
  uint32_t patches = 0;        ///< patches of the calibration mesh
  std::vector<DrawCost> draw;  ///< RT(tf), ascending tess, Bézier patches
  /// RT(tf) of Gregory patches relative to Bézier ones at the same level (1 if unmeasured).
  double gregoryDrawFactor = 1.0;
  double drawZeroMsPerPatch = 0.0;  ///< RT0: a patch in a draw with tessellation factor 0
  double submitMs = 0.0;            ///< one empty submission and wait
  double cullDispatchMs = 0.0;      ///< the fixed cost of one cull dispatch (no patches)
  std::map<std::string, double> cullMsPerPatch;  ///< CT per stage (see above)
  /// Hi-Z build against level 0's pixel count, ascending: half-resolution pyramids of two
  /// image sizes and a full-resolution one (HiZOptions::fullResolution).
  std::vector<SizeCost> hizBuild;
  double pointUpdateCpuMsPerPatch = 0.0;  ///< cage → control points on the CPU
  double pointUpdateGpuMsPerPatch = 0.0;  ///< the same in Vulkan compute
  double boundsMsPerPatch = 0.0;          ///< the bounds pass of TCONE (the update's)
  /// The bounds pass per back-patch method name ("tcone", "ncone", "tangent-plane", ...)
  /// and per displaced extension ("acon", "con": the cones of a deforming displaced mesh):
  /// each writes other cull data (frame/cull/bounds_pass.h), at its own cost.
  std::map<std::string, double> boundsMsPerMethod;
  /// RT(tf) of a displaced patch over that of the same patch undisplaced (the displacement
  /// lookup in the evaluation stage), per measured level, ascending (empty: 1).
  std::vector<std::pair<uint32_t, double>> displacedDrawFactor;
  /// The back-patch accuracies (docs/algorithms/drawn-triangles.md). Surface-exact (the
  /// papers' test, CullSettings::drawnTriangles off): CT per method, like cullMsPerPatch.
  std::map<std::string, double> surfaceCullMsPerPatch;
  /// The listed-triangle test (CullSettings::drawnEnumerate) per method: what it adds to the
  /// method's drawn-triangle bound kernel, per patch it runs on (those the surface test
  /// culls and the bound keeps), against the uniform tessellation level (it lists the
  /// level's triangles), ascending levels.
  std::map<std::string, std::vector<std::pair<uint32_t, double>>> listedCullMsPerPatch;
  /// What the tight Hi-Z lookup (bound::HiZLookup::Tight: one level finer where the box
  /// still touches at most 2x2 texels) adds to the occlusion stage's CT over the paper's
  /// lookup, per patch; nullopt when not measured (then the plan keeps the paper's).
  std::optional<double> hizTightMsPerPatch;

  /// \brief RT(tf) per Bézier patch at any level: linear in (tf + 1)² between the measured
  /// levels (the work is (tf + 1)² evaluations), extrapolated with the last two.
  /// \throws osd_cull::Error without draw samples.
  double drawMs(double tess) const;
  /// \brief The same for DrawCost::backMsPerPatch.
  double backDrawMs(double tess) const;
  /// \brief displacedDrawFactor at any level, linear in (tf + 1)² between the measured
  /// levels (constant beyond them); 1 when unmeasured.
  double displacedDrawFactorAt(double tess) const;
  /// \brief The bounds pass per patch of back-patch method `method`: its own measurement
  /// (boundsMsPerMethod), else that of the method it shares its pass with (tangent-plane-16:
  /// tangent-plane; the fp64 variants: their fp32 method), else boundsMsPerPatch.
  double boundsMs(const std::string& method) const;
  /// \brief What the listed-triangle test adds to back-patch method `method`'s CT at level
  /// `tess`: linear in (tf + 1)² (the triangles it lists) between the measured levels,
  /// extrapolated with the last two. \throws osd_cull::Error when not measured for `method`.
  double listedCullMs(const std::string& method, double tess) const;
  /// \brief CT of a stage. \throws osd_cull::Error naming the stage when it is not measured.
  double cullMs(const std::string& stage) const;
  /// \brief The Hi-Z build of a depth image of `pixels`: linear between the samples,
  /// proportional beyond them. \throws osd_cull::Error without samples.
  double hizBuildMs(uint64_t pixels) const;
};

/// \brief The calibration as text: `name value...` lines (stable, diffable, versioned).
std::string toText(const Calibration& calibration);
/// \brief Parses toText()'s output, validated whole: every entry present (the closing `end`
/// line too, so that a file cut at a line boundary is refused), once, and every number
/// finite and in range (times in [0, 1e4] ms, counts and levels in their ranges).
/// \throws osd_cull::Error naming `source`, the line or the missing entry, and what was
/// expected.
Calibration fromText(const std::string& text, const std::string& source);

/// \brief The cache directory, or an empty path when disabled (see the file comment).
std::filesystem::path calibrationCacheDirectory();
/// \brief The file of `key` in the cache directory (a hash of the key in the name; the key
/// itself is stored inside and compared on load).
std::filesystem::path calibrationCacheFile(const CalibrationKey& key);
/// \brief The cached calibration of `key`; nullopt when the cache is off, has none, or the
/// file is of another key. A file of an older format or a damaged one (cut short, a field
/// missing, out of range: fromText()): with `outdated`, nullopt and the message, naming the
/// file and the field, in *outdated (so that the caller measures again, as every command
/// does); without, an Error saying so.
std::optional<Calibration> loadCachedCalibration(const CalibrationKey& key,
                                                 std::string* outdated = nullptr);
/// \brief "calibration file format N, this library reads format M ...: measure it again".
std::string outdatedCalibrationMessage(int format);
/// \brief Reads a calibration file. \throws osd_cull::Error (file, line, problem).
Calibration loadCalibration(const std::filesystem::path& file);
/// \brief Writes `calibration` to `file` (through a temporary name, then renamed),
/// creating its directory. \throws osd_cull::Error when it cannot be written.
void storeCalibration(const Calibration& calibration, const std::filesystem::path& file);

}  // namespace osd_cull::plan
