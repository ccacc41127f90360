// bench-extraction: BigGuy at isolation levels 1..4, osd_cull's patch extraction and
// per-frame control-point update next to OpenSubdiv's own path, measured in the same run.
//
//   ours, set-up:     extractPatches (refiner, adaptive refinement, patch table, stencils,
//                     composed cage → control-point matrix, points)
//   OpenSubdiv set-up: refiner, adaptive refinement, Far::PatchTable, Far::StencilTable
//   ours, per frame:  PatchPointMatrix::update, float xyz in and out (and the double version)
//   OpenSubdiv, per frame: StencilTable::UpdateValues, PatchTable::ComputeLocalPointValues,
//                     then per regular patch the boundary extrapolation and B-spline → Bézier
//                     conversion, per Gregory patch a gather of its 20 points, into the same
//                     PatchSet layout (float, as OpenSubdiv's default precision).
//
// Usage: bench-extraction [--mesh FILE] [--levels MAX] [--repeats N] [--write FILE.md]
// The table goes to stdout (markdown), progress to stderr.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/error.h"
#include "osd_cull/patch/bspline_bezier.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/version.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace osd_cull;
using Clock = std::chrono::steady_clock;

// Runs the tasks in turn, `repeats` rounds (interleaved, so a burst of load on the shared
// machine hits all of them alike), and returns the median wall time of each in milliseconds.
std::vector<double> interleavedMedianMs(int repeats,
                                        const std::vector<std::function<void()>>& tasks) {
  std::vector<std::vector<double>> times(tasks.size());
  for (int i = 0; i < repeats; ++i)
    for (std::size_t t = 0; t < tasks.size(); ++t) {
      const auto start = Clock::now();
      tasks[t]();
      times[t].push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
  std::vector<double> medians;
  for (std::vector<double>& v : times) {
    std::sort(v.begin(), v.end());
    medians.push_back(v[v.size() / 2]);
  }
  return medians;
}

struct FloatVertex {
  float x = 0, y = 0, z = 0;
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const FloatVertex& s, float w) {
    x += w * s.x;
    y += w * s.y;
    z += w * s.z;
  }
};

// OpenSubdiv's own path, float precision (its default).
struct OsdPath {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<const Far::PatchTable> table;
  std::unique_ptr<const Far::StencilTable> stencils;
  std::vector<FloatVertex> vertices;  // coarse | refined (all levels) | local points
  std::array<std::array<float, 16>, 16> conversion[16];

  OsdPath(const CageMesh& cage, int level) {
    refiner = makeTopologyRefiner(cage);
    Far::PatchTableFactory::Options po(static_cast<unsigned>(level));
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = true;
    po.generateVaryingTables = false;
    refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
    table.reset(Far::PatchTableFactory::Create(*refiner, po));
    Far::StencilTableFactory::Options so;
    so.generateIntermediateLevels = true;
    so.generateOffsets = true;
    stencils.reset(Far::StencilTableFactory::Create(*refiner, so));
    vertices.resize(
        static_cast<size_t>(refiner->GetNumVerticesTotal() + table->GetNumLocalPoints()));
    for (unsigned mask = 0; mask < 16; ++mask)
      for (int r = 0; r < 16; ++r)
        for (int k = 0; k < 16; ++k)
          conversion[mask][r][k] = static_cast<float>(bsplineToBezierWeights(mask)[r][k]);
  }

  // Bytes of the tables one frame reads: stencil sizes, indices and float weights,
  // local-point stencils, patch point indices and boundary masks.
  double tableMegabytes() const {
    auto stencilBytes = [](const Far::StencilTable& t) {
      return 4.0 * t.GetNumStencils() + 8.0 * static_cast<double>(t.GetControlIndices().size());
    };
    double bytes = stencilBytes(*stencils);
    if (const Far::StencilTable* local = table->GetLocalPointStencilTable())
      bytes += stencilBytes(*local);
    bytes += 4.0 * table->GetNumControlVerticesTotal() + 8.0 * table->GetNumPatchesTotal();
    return bytes / 1e6;
  }

  // One frame: cage xyz in, all patch control points out (Bézier first, then Gregory).
  void update(const std::vector<float>& cage, std::vector<float>& out) {
    const int coarse = refiner->GetLevel(0).GetNumVertices();
    for (int i = 0; i < coarse; ++i) vertices[i] = {cage[3 * i], cage[3 * i + 1], cage[3 * i + 2]};
    stencils->UpdateValues(vertices.data(), vertices.data() + coarse);
    table->ComputeLocalPointValues(vertices.data(),
                                   vertices.data() + refiner->GetNumVerticesTotal());
    float* o = out.data();
    for (int pass = 0; pass < 2; ++pass)
      for (int a = 0; a < table->GetNumPatchArrays(); ++a) {
        const bool regular =
            table->GetPatchArrayDescriptor(a).GetType() == Far::PatchDescriptor::REGULAR;
        if (regular != (pass == 0)) continue;
        for (int p = 0; p < table->GetNumPatches(a); ++p) {
          const Far::ConstIndexArray cvs = table->GetPatchVertices(a, p);
          if (!regular) {
            for (int k = 0; k < cvs.size(); ++k, o += 3) {
              const FloatVertex& v = vertices[static_cast<size_t>(cvs[k])];
              o[0] = v.x, o[1] = v.y, o[2] = v.z;
            }
            continue;
          }
          const auto& w = conversion[table->GetPatchParam(a, p).GetBoundary() & 15u];
          for (int r = 0; r < 16; ++r, o += 3) {
            float x = 0, y = 0, z = 0;
            for (int k = 0; k < 16; ++k) {
              if (w[r][k] == 0.0f) continue;
              const FloatVertex& v = vertices[static_cast<size_t>(cvs[k])];
              x += w[r][k] * v.x, y += w[r][k] * v.y, z += w[r][k] * v.z;
            }
            o[0] = x, o[1] = y, o[2] = z;
          }
        }
      }
  }
};

struct Row {
  int level = 0;
  ExtractionStats stats;
  double oursSetupMs = 0, osdSetupMs = 0;
  double oursFloatMs = 0, oursDoubleMs = 0, osdFrameMs = 0;
  double maxDiff = 0;  // |ours - OpenSubdiv| / bounding-box diagonal, float path
  double oursTableMb = 0, osdTableMb = 0;  // tables read per frame (float weights)
};

std::string fmt(double v, int digits = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// The 1-minute load average (other processes share this machine's cores and caches).
std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string first;
  in >> first;
  return first.empty() ? std::string("unknown") : first;
}

std::string machineNote() {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.starts_with("model name")) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream s;
  s << cpu << ", " << std::thread::hardware_concurrency() << " hardware threads (shared VM), "
    << "compiler " << __VERSION__
#ifdef __OPTIMIZE__
    << " (optimized build)"
#else
    << " (unoptimized build)"
#endif
    << ", OpenSubdiv " << OPENSUBDIV_VERSION_MAJOR << "." << OPENSUBDIV_VERSION_MINOR << "."
    << OPENSUBDIV_VERSION_PATCH << ". Single-threaded CPU code on both sides.";
  return s.str();
}

// One level: set-up of both sides (interleaved), then their per-frame updates (interleaved),
// table sizes and the largest difference of the two float outputs relative to `diag`.
Row measureLevel(const CageMesh& cage, const std::vector<float>& cageXyz, double diag, int level,
                 int setupRepeats, int repeats) {
  std::cerr << "level " << level << ": extraction..." << std::flush;
  Row row;
  row.level = level;
  PatchOptions options;
  options.isolationLevel = level;
  PatchExtraction ex;
  std::unique_ptr<OsdPath> osd;
  const std::vector<double> setup =
      interleavedMedianMs(setupRepeats, {[&] { ex = extractPatches(cage, options); },
                                         [&] { osd = std::make_unique<OsdPath>(cage, level); }});
  row.oursSetupMs = setup[0];
  row.osdSetupMs = setup[1];
  row.stats = ex.stats;

  std::cerr << " per-frame update..." << std::flush;
  std::vector<float> ours(3 * ex.patches.points.size()), theirs(ours.size());
  std::vector<glm::dvec3> oursDouble(ex.patches.points.size());
  const std::vector<double> frame =
      interleavedMedianMs(repeats, {[&] { ex.matrix.update(cageXyz, ours); },
                                    [&] { ex.matrix.update(cage.positions, oursDouble); },
                                    [&] { osd->update(cageXyz, theirs); }});
  row.oursFloatMs = frame[0];
  row.oursDoubleMs = frame[1];
  row.osdFrameMs = frame[2];
  row.oursTableMb =
      (4.0 * ex.matrix.rowCount() + 8.0 * static_cast<double>(ex.matrix.nonZeroCount())) / 1e6;
  row.osdTableMb = osd->tableMegabytes();
  for (size_t i = 0; i < ours.size(); ++i)
    row.maxDiff = std::max(row.maxDiff, double(std::abs(ours[i] - theirs[i])));
  row.maxDiff /= diag;
  std::cerr << " done\n";
  return row;
}

// The Markdown table of the rows.
std::string formatTable(const std::vector<Row>& rows) {
  std::ostringstream table;
  table << "| level | patches | Bézier | Gregory | control points | matrix non-zeros "
           "| set-up ms, ours | set-up ms, OpenSubdiv | ratio "
           "| per frame ms, ours (float) | per frame ms, ours (double) | per frame ms, "
           "OpenSubdiv (float) | ratio (float) "
           "| tables MB, ours / OpenSubdiv | max diff / diag |\n";
  table << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    const uint32_t bezier =
        r.stats.regular + r.stats.boundary + r.stats.corner + r.stats.bsplineEndCaps;
    char diff[32];
    std::snprintf(diff, sizeof diff, "%.1e", r.maxDiff);
    table << "| " << r.level << " | " << r.stats.patches() << " | " << bezier << " | "
          << r.stats.gregory << " | " << r.stats.controlPoints << " | " << r.stats.matrixNonZeros
          << " | " << fmt(r.oursSetupMs) << " | " << fmt(r.osdSetupMs) << " | "
          << fmt(r.oursSetupMs / r.osdSetupMs) << " | " << fmt(r.oursFloatMs, 3) << " | "
          << fmt(r.oursDoubleMs, 3) << " | " << fmt(r.osdFrameMs, 3) << " | "
          << fmt(r.oursFloatMs / r.osdFrameMs) << " | " << fmt(r.oursTableMb, 1) << " / "
          << fmt(r.osdTableMb, 1) << " | " << diff << " |\n";
  }
  return table.str();
}

// What --write puts on the page around the table.
struct PageFacts {
  std::filesystem::path mesh;
  int vertices = 0, faces = 0;
  int setupRepeats = 0, repeats = 0, maxLevel = 0;
  std::string loadBefore, loadAfter;
};

void writePage(const std::string& path, const std::string& table, const PageFacts& f) {
  std::ofstream out(path);
  if (!out) throw Error("bench-extraction: cannot write " + path);
  out << "# Patch extraction and per-frame update: osd_cull vs OpenSubdiv\n\n"
      << "Mesh: `" << f.mesh.filename().string() << "` (" << f.vertices << " cage vertices, "
      << f.faces << " faces), Gregory-basis end caps, infinitely sharp patches on.\n"
      << "Medians of " << f.setupRepeats << " set-ups and " << f.repeats
      << " per-frame updates, both sides in the same run, interleaved round by round.\n\n"
      << table << "\n"
      << "- *set-up, ours*: `extractPatches` — topology refiner, adaptive refinement, "
         "`Far::PatchTable`, "
         "double-precision refinement and local-point stencils, the composed cage → "
         "control-point matrix "
         "and the points.\n"
      << "- *set-up, OpenSubdiv*: topology refiner, adaptive refinement, `Far::PatchTable`, "
         "float "
         "`Far::StencilTable` (what an OpenSubdiv program builds before its first frame).\n"
      << "- *per frame, ours*: one pass of `PatchPointMatrix::update` over all control points "
         "(float xyz "
         "arrays; the double column uses `glm::dvec3`).\n"
      << "- *per frame, OpenSubdiv*: `StencilTable::UpdateValues`, "
         "`PatchTable::ComputeLocalPointValues`, then "
         "per regular patch the boundary extrapolation and B-spline → Bézier conversion and "
         "per Gregory "
         "patch a gather of its 20 points, into the same layout.\n"
      << "- *ratio* = ours / OpenSubdiv (below 1: ours is faster).\n"
      << "- *tables MB*: what one frame reads besides the cage and the output: for ours the "
         "row "
         "sizes, column indices and float weights of the matrix; for OpenSubdiv the refinement "
         "and local-point stencil tables, patch point indices and patch params. The composed "
         "matrix saves the intermediate refined vertices and the per-patch conversion "
         "arithmetic, but it reads more memory, so its per-frame time suffers more when "
         "other processes compete for the caches (see the load average below).\n"
      << "- *max diff / diag*: largest coordinate difference between the two float outputs, "
         "relative to "
         "the bounding-box diagonal.\n\n"
      << "Machine: " << machineNote() << " Load average (1 min) " << f.loadBefore << " before and "
      << f.loadAfter << " after the run."
      << " Run-to-run variation on this VM is up to 1.5x; compare "
         "within a run.\n\n"
      << "Command (from the build directory):\n\n"
      << "    ./benchmarks/bench-extraction --repeats " << f.repeats << " --levels " << f.maxLevel
      << " --write ../docs/results/extraction.md\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path dataDir =
      std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data";
  if (const char* env = std::getenv("OSD_CULL_DATA_DIR"); env && *env) dataDir = env;
  std::filesystem::path mesh = dataDir / "characters" / "bigguy.obj";
  int maxLevel = 4, repeats = 30;
  std::string writePath;
  std::string meshFile = mesh.string();
  try {
    if (!bench::CommandLine("bench-extraction", "bench_extraction.cpp")
             .text("--mesh", meshFile)
             .integer("--levels", maxLevel, 0)
             .integer("--repeats", repeats, 1)
             .text("--write", writePath)
             .parse(argc, argv))
      return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench-extraction: " << e.what() << "\n";
    return 2;
  }
  mesh = meshFile;

  try {
    const CageMesh cage = adapters::loadCage(mesh);
    std::vector<float> cageXyz;
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& p : cage.positions) {
      cageXyz.insert(cageXyz.end(), {float(p.x), float(p.y), float(p.z)});
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const double diag = glm::length(hi - lo);
    const int setupRepeats = std::max(1, repeats / 6);
    const std::string loadBefore = loadAverage();

    std::vector<Row> rows;
    for (int level = 1; level <= maxLevel; ++level)
      rows.push_back(measureLevel(cage, cageXyz, diag, level, setupRepeats, repeats));
    const std::string table = formatTable(rows);
    std::cout << table;
    if (!writePath.empty()) {
      writePage(writePath, table,
                {mesh, cage.vertexCount(), cage.faceCount(), setupRepeats, repeats, maxLevel,
                 loadBefore, loadAverage()});
      std::cerr << "wrote " << writePath << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "bench-extraction: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
