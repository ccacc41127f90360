// osd_cull dropped into an existing Vulkan + OpenSubdiv program (docs/integration.md).
//
//   osd-cull-integration [--frames N] [--size WxH] [--out FILE.png] [--validate]
//
// The program has its own Vulkan device (app_vulkan.*: instance, device, queue, its
// B8G8R8A8 color and D32 depth images, its render passes, command buffer and fence) and
// its own Osd::Mesh (on osd_cull's Vulkan backend). Each frame it animates the cage,
// refines it with the Osd::Mesh, and lets osd_cull cull and draw the patches into its
// attachments. At the end its image is compared with osd_cull's own renderer drawing the
// same patches unculled: the program fails when they differ or validation complained.
#include "app_vulkan.h"
#include "lend.h"
#include "osd_cull/frame/cull_frame.h"
#include "adapters/image_png.h"
#include "osd_cull/osd/gpu_point_update.h"
#include "osd_cull/osd/mesh.h"
#include "osd_cull/patch/application_patches.h"
#include "osd_cull/patch/refiner.h"
#include "osd_cull/scene/procedural.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace osd_cull;

struct Options {
  int frames = 4;
  uint32_t width = 320, height = 240;
  std::string out;
  bool validation = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("option " + a + " needs a value");
      return argv[++i];
    };
    if (a == "--frames") {
      o.frames = std::stoi(value());
    } else if (a == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%ux%u", &o.width, &o.height) != 2)
        throw std::runtime_error("--size wants WxH, got " + v);
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--validate") {
      o.validation = true;
    } else {
      throw std::runtime_error("unknown option " + a);
    }
  }
  if (o.frames < 1) throw std::runtime_error("--frames must be at least 1");
  return o;
}

// The one place osd_cull draws into the program's frame: the two-pass culled frame,
// recorded into the program's command buffer (osd_cull never submits it), submitted and
// waited for by the program; the frame's statistics are read after its fence.
frame::CullFrameStats drawCulled(frame::CullFrame& cull, app::Commands& commands,
                                 const frame::Camera& camera) {
  VkCommandBuffer cmd = commands.begin();
  const uint64_t frame = cull.record(cmd, camera, {});
  commands.submitAndWait();
  const std::optional<frame::CullFrameStats> stats = cull.stats(frame);
  if (!stats) throw std::runtime_error("the statistics of a finished frame are missing");
  return *stats;
}

// A non-rigid wobble of the cage, frame by frame.
std::vector<float> animatedCage(const CageMesh& cage, int frame) {
  std::vector<float> xyz;
  for (size_t v = 0; v < cage.positions.size(); ++v) {
    const glm::dvec3 p =
        cage.positions[v] + 0.08 * std::sin(0.9 * frame + 1.7 * double(v)) * glm::dvec3(0, 0, 1);
    xyz.insert(xyz.end(), {float(p.x), float(p.y), float(p.z)});
  }
  return xyz;
}

int run(const Options& options) {
  app::Device device({.validation = options.validation});
  app::Target target(device.physical, device.device, options.width, options.height);
  app::Commands commands(device.device, device.queue, device.family);
  std::printf("application device: %s\n", device.name.c_str());

  uint32_t differ = 0, pixels = 0;
  {
    // osd_cull on the program's device: owns none of the handles it is lent.
    vulkan::Context context(lendDevice(device));
    osd::DeviceContext osdDevice(context);
    osd::VkEvaluatorCache evaluators;

    // The program's Osd::Mesh, feature-adaptive with Gregory-basis end caps.
    const CageMesh cage = scene::defaultMesh();
    OpenSubdiv::Osd::MeshBitset bits;
    bits.set(OpenSubdiv::Osd::MeshAdaptive);
    bits.set(OpenSubdiv::Osd::MeshEndCapGregoryBasis);
    bits.set(OpenSubdiv::Osd::MeshUseInfSharpPatch);
    osd::VkMesh mesh(makeTopologyRefiner(cage).release(), 3, 0, 2, bits, &evaluators, &osdDevice);

    // osd_cull's patches from the mesh's own refiner and patch table (no second refinement),
    // their control points computed from the mesh's refined vertex buffer.
    const ApplicationPatches patches = extractApplicationPatches(
        *mesh.GetTopologyRefiner(), *mesh.GetFarPatchTable(), cage.positions, cage.source);
    osd::GpuPointUpdate points(osdDevice, patches.fromPatchPoints, {4});
    frame::GpuPatchSet gpu(context, patches.extraction.patches);
    gpu.readPointsFrom(context, points.points(), 4);

    frame::RenderTarget lentTarget(context, lendTarget(target));
    frame::Renderer renderer(context);
    frame::CullFrameOptions cullOptions;
    cullOptions.render.tessellation.uniformLevel = 4;
    const frame::CullMesh meshes[] = {{&gpu, &patches.extraction.patches}};
    frame::CullFrame cull(context, renderer, lentTarget, meshes, cullOptions);

    const frame::Bounds bounds = frame::boundsOf(patches.extraction.patches.points);
    frame::Camera camera;
    for (int f = 0; f < options.frames; ++f) {
      const std::vector<float> xyz = animatedCage(cage, f);
      mesh.UpdateVertexBuffer(xyz.data(), 0, cage.vertexCount());
      mesh.Refine();
      points.updateFrom(*mesh.GetVertexBuffer());
      camera = frame::orbit(frame::frameBounds(bounds, {1.0, 0.6, 1.4}, {0, 1, 0}, 40.0,
                                               options.width, options.height),
                            bounds.center(), {0, 1, 0}, 6.0 * f);
      const frame::CullFrameStats s = drawCulled(cull, commands, camera);
      std::printf(
          "frame %d: %u patches, drawn %u + %u, culled frustum %u, back-patch %u, "
          "occlusion %u\n",
          f, s.patchesTotal, s.drawnPass1, s.drawnPass2, s.culledFrustum, s.culledBackPatch,
          s.culledOcclusion);
    }
    mesh.Synchronize();

    // The program's own read-back of its color image, against osd_cull's renderer drawing
    // every patch, unculled, into osd_cull's own target.
    const std::vector<uint8_t> bgra = target.readColor(commands);
    frame::RenderTarget own(context, options.width, options.height);
    frame::RenderOptions render = cullOptions.render;
    renderer.render(own, camera, gpu, &patches.extraction.patches, render);
    const std::vector<uint8_t> rgba = own.readColor(context);
    pixels = options.width * options.height;
    for (uint32_t p = 0; p < pixels; ++p)
      differ += bgra[4 * p + 2] != rgba[4 * p] || bgra[4 * p + 1] != rgba[4 * p + 1] ||
                bgra[4 * p] != rgba[4 * p + 2] || bgra[4 * p + 3] != rgba[4 * p + 3];
    if (!options.out.empty()) {
      std::vector<uint8_t> image = bgra;
      for (uint32_t p = 0; p < pixels; ++p) std::swap(image[4 * p], image[4 * p + 2]);
      adapters::writePng(options.out, adapters::colorImage(options.width, options.height, image));
      std::printf("wrote %s\n", options.out.c_str());
    }
  }
  std::printf("image vs osd_cull's renderer: %u of %u pixels differ\n", differ, pixels);
  std::printf("validation messages: %zu\n", device.validationMessages.size());
  // The culled image equals the unculled one exactly.
  const bool pass = differ == 0 && device.validationMessages.empty();
  std::printf("integration: %s\n", pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) try {
  return run(parse(argc, argv));
} catch (const std::exception& e) {
  std::fprintf(stderr, "osd-cull-integration: error: %s\n", e.what());
  return 1;
}
