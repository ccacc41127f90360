// Animated meshes (docs/results/animation.md): BigGuy with the limb skinning rig
// (scene::SkinningRig::Limbs), culled by the two-pass frame with the GPU bounds pass.
//
// Usage: bench-animation [--only 1234] [--size N] [--frames N] [--csv DIR]
//   1. cull rate and not-drawn share against deformation speed (Niessner & Loop Fig. 9
//      right, for motion of the mesh instead of the camera);
//   2. per-frame cost of point update + bounds pass + cull + draw, animated (CPU and GPU
//      point update) against static, frames interleaved, at tessellation 4 and 16;
//   3. bounds pass (back-patch data of every method, displaced ACoN and CoN cones) and cull
//      kernel in ns per patch, interleaved;
//   4. back-patch cull rates with cones from the GPU bounds pass against host-built cones.
#include "adapters/load_mesh.h"
#include "bench_support.h"
#include "osd_cull/bound/back_patch_validity.h"
#include "osd_cull/bound/drawn_triangles.h"
#include "osd_cull/error.h"
#include "osd_cull/frame/cull/bounds_pass.h"
#include "osd_cull/frame/cull/cull_pass.h"
#include "osd_cull/frame/cull_frame.h"
#include "osd_cull/frame/dynamic_patch_mesh.h"
#include "osd_cull/frame/verify/view_sets.h"
#include "osd_cull/patch/extract_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/cage_animation.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "osd_cull/vk/context.h"

#include <glm/geometric.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull {
namespace {

using bound::BackPatchMethod;

struct Options {
  std::string only = "1234";
  uint32_t size = 384;
  int frames = 12;
  std::string csvDir;
};

// The options; false after --help.
bool parse(int argc, char** argv, Options& o) {
  return bench::CommandLine("bench-animation", "bench_animation.cpp")
      .text("--only", o.only)
      .number("--size", o.size, 1)
      .integer("--frames", o.frames, 1)
      .text("--csv", o.csvDir)
      .parse(argc, argv);
}

std::filesystem::path dataDir() {
  if (const char* d = std::getenv("OSD_CULL_DATA_DIR")) return d;
  return std::filesystem::path(OSD_CULL_SOURCE_DIR) / ".." / "shared" / "data";
}

struct Character {
  CageMesh cage;
  bound::BackPatchValidity validity;
  std::unique_ptr<scene::CageAnimation> skin;  // one cycle per second
};

Character bigGuy(double swingDegrees) {
  Character c;
  c.cage = adapters::loadCage(dataDir() / "characters" / "bigguy.obj");
  c.validity = bound::backPatchValidity(summarize(*makeTopologyRefiner(c.cage)),
                                        bound::signedVolume(c.cage));
  scene::SkinningParams s;
  s.rig = scene::SkinningRig::Limbs;
  s.swingDegrees = swingDegrees;
  s.frequency = 1.0;
  c.skin = scene::makeSkinning(c.cage.positions, s);
  return c;
}

frame::Camera viewOf(const frame::Bounds& b, int view, uint32_t size) {
  const glm::dvec3 dirs[] = {{0.3, 0.25, 1.0}, {1.0, 0.2, -0.4}, {-0.6, 0.5, -1.0}};
  return frame::frameBounds(b, dirs[view % 3], {0, 1, 0}, 40.0, size, size);
}

// 1. Cull rate against speed: the skinning phase advances `step` degrees of its cycle per
// frame (joint angles change by up to swing * step * π / 180 per frame).
void speedSweep(vulkan::Context& context, const Options& o) {
  Character c = bigGuy(40.0);
  std::printf(
      "## Cull rate against deformation speed (BigGuy level 2, limb rig, swing 40 deg, "
      "tess 4, %ux%u, 3 views, %d frames each after 3 warm-up frames)\n\n",
      o.size, o.size, o.frames);
  std::printf(
      "| stages | phase step (deg/frame) | max joint turn (deg/frame) | max vertex move "
      "(%% of diagonal) | cull rate | not drawn | TES / unculled "
      "|\n|---|---:|---:|---:|---:|---:|---:|\n");
  std::ofstream csv;
  if (!o.csvDir.empty()) {
    csv.open(std::filesystem::path(o.csvDir) / "animation_speed.csv");
    csv << "stages,step,joint_deg,move_pct,cull_rate,not_drawn,tes_ratio\n";
  }
  const double steps[] = {0, 3, 6, 12, 24, 48};
  for (const char* stages : {"hiz", "tcone+hiz"}) {
    for (double step : steps) {
      frame::DynamicPatchMesh mesh(context, c.cage);
      frame::CullFrameOptions fo;
      fo.render.tessellation.uniformLevel = 4;
      fo.cull = {true, std::string(stages) == "hiz" ? "" : "tcone", "hiz", c.validity};
      const frame::CullMesh meshes[] = {{.gpu = &mesh.gpu(),
                                         .host = &mesh.patches(),
                                         .cullData = &mesh.cullData(BackPatchMethod::TCone)}};
      frame::RenderTarget target(context, o.size, o.size);
      frame::Renderer renderer(context);
      const frame::Bounds bounds = frame::boundsOf(mesh.patches().points);
      const double diagonal = glm::length(bounds.hi - bounds.lo);
      double culled = 0, notDrawn = 0, tes = 0, n = 0, move = 0;
      // Tessellation work of drawing every patch (transition edges tessellate finer, so not
      // simply patches x 25): one unculled draw, counted by pipeline statistics.
      const uint64_t fullTes =
          renderer.render(target, viewOf(bounds, 0, o.size), mesh.gpu(), &mesh.patches(), fo.render)
              .statistics.tessEvaluationInvocations;
      std::vector<glm::dvec3> positions(c.cage.positions.size()), last;
      for (int view = 0; view < 3; ++view) {
        frame::CullFrame cull(context, renderer, target, meshes, fo);
        const frame::Camera camera = viewOf(bounds, view, o.size);
        for (int f = 0; f < o.frames + 3; ++f) {
          c.skin->positions(f * step / 360.0 + 0.1 * view, positions);
          if (!last.empty() && f >= 3)
            for (size_t i = 0; i < positions.size(); ++i)
              move = std::max(move, glm::length(positions[i] - last[i]) / diagonal);
          last = positions;
          mesh.setCagePositions(positions);
          mesh.update();
          const frame::CullFrameStats s = cull.render(camera, {});
          if (f < 3) continue;
          culled += double(s.culled()) / s.patchesTotal;
          notDrawn += 1.0 - double(s.drawnPass1 + s.drawnPass2) / s.patchesTotal;
          tes += double(s.pass1.tessEvaluationInvocations + s.pass2.tessEvaluationInvocations) /
                 double(fullTes);
          ++n;
        }
        last.clear();
      }
      const double joint = 40.0 * step * 3.14159265358979 / 180.0;
      std::printf("| %s | %.0f | %.1f | %.2f | %.1f%% | %.1f%% | %.3f |\n", stages, step, joint,
                  100 * move, 100 * culled / n, 100 * notDrawn / n, tes / n);
      std::fflush(stdout);
      if (csv)
        csv << stages << "," << step << "," << joint << "," << 100 * move << "," << culled / n
            << "," << notDrawn / n << "," << tes / n << "\n";
    }
  }
}

// 2. Per-frame cost, three meshes of BigGuy culled by their own frames, frames interleaved.
void frameCost(vulkan::Context& context, const Options& o) {
  Character c = bigGuy(40.0);
  std::printf(
      "\n## Per-frame cost, animated against static (BigGuy level 2, frustum + tcone + "
      "hiz, %ux%u, medians of %d interleaved frames, wall ms)\n\n",
      o.size, o.size, o.frames);
  std::printf(
      "| tess | mesh | points | bounds | cull (pyramid + kernel) | draw (both passes) | "
      "frame | update + bounds share |\n|---:|---|---:|---:|---:|---:|---:|---:|\n");
  for (uint32_t tess : {4u, 16u}) {
    struct Run {
      const char* name;
      frame::PointUpdatePath path;
      bool animated;
      std::unique_ptr<frame::DynamicPatchMesh> mesh;
      std::unique_ptr<frame::CullFrame> frame;
      std::unique_ptr<frame::RenderTarget> target;
      std::vector<double> points, bounds, cull, draw, total;
    };
    Run runs[] = {
        {"static", frame::PointUpdatePath::Cpu, false, {}, {}, {}, {}, {}, {}, {}, {}},
        {"animated, CPU update", frame::PointUpdatePath::Cpu, true, {}, {}, {}, {}, {}, {}, {}, {}},
        {"animated, GPU update",
         frame::PointUpdatePath::Gpu,
         true,
         {},
         {},
         {},
         {},
         {},
         {},
         {},
         {}}};
    frame::Renderer renderer(context);
    frame::CullFrameOptions fo;
    fo.render.tessellation.uniformLevel = tess;
    fo.cull = {true, "tcone", "hiz", c.validity};
    for (Run& r : runs) {
      r.mesh = std::make_unique<frame::DynamicPatchMesh>(context, c.cage, PatchOptions{}, r.path);
      r.target = std::make_unique<frame::RenderTarget>(context, o.size, o.size);
      const frame::CullMesh meshes[] = {{.gpu = &r.mesh->gpu(),
                                         .host = &r.mesh->patches(),
                                         .cullData = &r.mesh->cullData(BackPatchMethod::TCone)}};
      r.frame = std::make_unique<frame::CullFrame>(context, renderer, *r.target, meshes, fo);
    }
    const frame::Camera camera = viewOf(frame::boundsOf(runs[0].mesh->patches().points), 0, o.size);
    std::vector<glm::dvec3> positions(c.cage.positions.size());
    for (int f = 0; f < o.frames + 2; ++f) {
      c.skin->positions(f / 30.0, positions);
      for (Run& r : runs) {
        double pointsMs = 0, boundsMs = 0;
        if (r.animated) {
          r.mesh->setCagePositions(positions);
          r.mesh->update();
          pointsMs = r.mesh->lastTimes().pointsMs;
          boundsMs = r.mesh->lastTimes().boundsMs;
        } else if (r.mesh->update()) {
          throw Error("a static mesh ran an update");
        }
        const frame::CullFrameStats s = r.frame->render(camera, {});
        if (f < 2) continue;  // pipelines warm
        r.points.push_back(pointsMs);
        r.bounds.push_back(boundsMs);
        r.cull.push_back(s.pyramidMs + s.cullMs);
        r.draw.push_back(s.pass1Ms + s.pass2Ms);
        r.total.push_back(pointsMs + boundsMs + s.totalMs());
      }
    }
    for (const Run& r : runs) {
      const double total = bench::median(r.total);
      std::printf("| %u | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f%% |\n", tess, r.name,
                  bench::median(r.points), bench::median(r.bounds), bench::median(r.cull),
                  bench::median(r.draw), total,
                  100 * (bench::median(r.points) + bench::median(r.bounds)) / total);
    }
    std::fflush(stdout);
  }
}

// 3. Bounds pass against cull kernel, ns per patch, interleaved: the back-patch data of
// each method (tangent plane: Gregory TCONE and G, H) and the displaced cones (ACoN, CoN,
// procedural map; issue 11), next to the cull kernels that read them.
void kernels(vulkan::Context& context, const Options& o) {
  Character c = bigGuy(40.0);
  PatchExtraction ex = extractPatches(c.cage);
  const std::vector<glm::dvec2> uvCorners = ex.uvCorners;
  frame::DynamicPatchMesh mesh(context, std::move(ex), c.cage.positions);
  const PatchSet& host = mesh.patches();
  const bound::DisplacementMap map("procedural", 256, 256,
                                   scene::proceduralDisplacementTexels(256, 4), 1.5, 0.5);
  const auto ranges = bound::displacementRanges(host, uvCorners, map);
  frame::BoundsPass tcone(context, mesh.gpu(), BackPatchMethod::TCone);
  frame::BoundsPass ncone(context, mesh.gpu(), BackPatchMethod::NCone);
  frame::BoundsPass tplane(context, mesh.gpu(), BackPatchMethod::TangentPlane);
  frame::BoundsPass acon(context, mesh.gpu(), bound::DisplacedExtension::ACoN, ranges);
  frame::BoundsPass con(context, mesh.gpu(), bound::DisplacedExtension::CoN, ranges);
  frame::CullSettings st{true, "tcone", "", c.validity}, sn{true, "ncone", "", c.validity};
  frame::CullSettings sp{true, "tangent-plane", "", c.validity};
  frame::CullPass cullT(context, mesh.gpu(), host, st, tcone.cullData());
  frame::CullPass cullN(context, mesh.gpu(), host, sn, ncone.cullData());
  frame::CullPass cullP(context, mesh.gpu(), host, sp, tplane.cullData());
  const frame::Camera camera = viewOf(frame::boundsOf(host.points), 0, o.size);
  std::vector<double> bt, bn, bp, ba, bc, ct, cn, cp, ht, hn, hp, ha, hc;
  auto hostBuild = [&](BackPatchMethod m) {  // the double reference, one thread (no upload)
    const auto start = std::chrono::steady_clock::now();
    const auto cones = bound::buildPatchCones(host, m);
    double g = 0;
    for (uint32_t p = 0; p < host.bezierCount; ++p)
      g += bound::bezierDerivativeBounds(host.controlPoints(p)).g;
    if (cones.size() != host.patchCount() || !(g >= 0)) throw Error("host cones");
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  auto hostDisplaced = [&](bound::DisplacedExtension e) {  // the cones of the host path
    const auto start = std::chrono::steady_clock::now();
    double s = 0;
    for (uint32_t p = 0; p < host.patchCount(); ++p)
      s += bound::displacementCone(host, p, e).sinAngle;
    if (!(s >= 0)) throw Error("host displaced cones");
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  for (int i = 0; i < 2 * o.frames + 1; ++i) {
    ht.push_back(hostBuild(BackPatchMethod::TCone));
    hn.push_back(hostBuild(BackPatchMethod::NCone));
    hp.push_back(hostBuild(BackPatchMethod::TangentPlane));
    ha.push_back(hostDisplaced(bound::DisplacedExtension::ACoN));
    hc.push_back(hostDisplaced(bound::DisplacedExtension::CoN));
    bt.push_back(tcone.run(mesh.pointError()));
    bn.push_back(ncone.run(mesh.pointError()));
    bp.push_back(tplane.run(mesh.pointError()));
    ba.push_back(acon.run(mesh.pointError()));
    bc.push_back(con.run(mesh.pointError()));
    ct.push_back(cullT.run(camera));
    cn.push_back(cullN.run(camera));
    cp.push_back(cullP.run(camera));
  }
  const double n = host.patchCount();
  auto ns = [&](const std::vector<double>& v) { return bench::median(v) * 1e6 / n; };
  std::printf(
      "\n## Bounds pass and cull kernel (BigGuy level 2, %u patches: %u Bezier, %u "
      "Gregory; wall time of submit-and-wait, medians of %d interleaved runs)\n\n",
      host.patchCount(), host.bezierCount, host.gregoryCount, 2 * o.frames + 1);
  std::printf("| pass | ms | ns per patch | / TCONE bounds pass |\n|---|---:|---:|---:|\n");
  auto row = [&](const char* name, const std::vector<double>& v) {
    std::printf("| %s | %.2f | %.0f | %.2f |\n", name, bench::median(v), ns(v),
                bench::median(v) / bench::median(bt));
  };
  row("bounds pass, TCONE (+ Gregory TCONE, G, H)", bt);
  row("bounds pass, NCONE (+ Gregory TCONE, G, H)", bn);
  row("bounds pass, tangent plane (Gregory TCONE, G, H)", bp);
  row("bounds pass, displaced ACoN (TCONE + Gregory TCONE, Dmin/Dmax)", ba);
  row("bounds pass, displaced CoN (NCONE + Gregory TCONE, Dmin/Dmax)", bc);
  row("host reference in double, TCONE + G, H (1 thread, no upload)", ht);
  row("host reference in double, NCONE + G, H (1 thread, no upload)", hn);
  row("host reference in double, tangent plane: Gregory TCONE + G, H (1 thread)", hp);
  row("host reference in double, ACoN cones (1 thread, no upload)", ha);
  row("host reference in double, CoN cones (1 thread, no upload)", hc);
  row("cull kernel, frustum + tcone (+ draw commands)", ct);
  row("cull kernel, frustum + ncone (+ draw commands)", cn);
  row("cull kernel, frustum + tangent-plane (+ draw commands)", cp);
  std::fflush(stdout);
}

// 4. Cull rates of the cone methods with GPU-built and host-built cull data, same views.
void rates(vulkan::Context& context, const Options& o) {
  Character c = bigGuy(40.0);
  std::printf(
      "\n## Back-patch cull rates, GPU bounds pass against host-built cones (BigGuy "
      "level 2, skinned pose t = 0.3 s, 64 random sphere views, back-patch stage alone, "
      "drawn-triangle bound on)\n\n");
  std::printf("| method | host cones | GPU bounds pass | lost |\n|---|---:|---:|---:|\n");
  frame::DynamicPatchMesh mesh(context, c.cage);
  std::vector<glm::dvec3> positions(c.cage.positions.size());
  c.skin->positions(0.3, positions);
  mesh.setCagePositions(positions);
  mesh.update();
  const PatchSet& host = mesh.patches();
  frame::ViewSetOptions vo;
  vo.count = 64;
  vo.width = vo.height = o.size;
  const auto views = frame::randomViews(frame::boundsOf(host.points), vo);
  for (const char* m : {"tcone", "ncone"}) {
    const frame::CullSettings s{false, m, "", c.validity};
    frame::CullPass hostPass(context, mesh.gpu(), host, s);
    frame::CullPass gpuPass(context, mesh.gpu(), host, s,
                            mesh.cullData(frame::cullMethod(m).reference));
    double a = 0, b = 0;
    for (const frame::Camera& cam : views) {
      hostPass.run(cam);
      gpuPass.run(cam);
      a += hostPass.counts().survivors();
      b += gpuPass.counts().survivors();
    }
    const double total = double(host.patchCount()) * views.size();
    std::printf("| %s | %.2f%% | %.2f%% | %.2f points |\n", m, 100 * (1 - a / total),
                100 * (1 - b / total), 100 * (b - a) / total);
  }
  std::fflush(stdout);
}

}  // namespace
}  // namespace osd_cull

int main(int argc, char** argv) {
  using namespace osd_cull;
  try {
    Options o;
    if (!parse(argc, argv, o)) return 0;
    vulkan::Context context;
    std::printf("device: %s\n\n", context.info().name.c_str());
    auto want = [&](char c) { return o.only.find(c) != std::string::npos; };
    if (want('1')) speedSweep(context, o);
    if (want('2')) frameCost(context, o);
    if (want('3')) kernels(context, o);
    if (want('4')) rates(context, o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench-animation: %s\n", e.what());
    return 1;
  }
  return 0;
}
