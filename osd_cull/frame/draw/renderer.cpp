#include "osd_cull/frame/draw/renderer.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/draw/dynamic_rendering.h"
#include "osd_cull/frame/draw/gpu_displacement.h"
#include "osd_cull/frame/shader_variants.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/limits.h"
#include "osd_cull/vk/pipeline.h"

#include <osd_cull/shared/draw_layout.h>

#include <array>
#include <chrono>

namespace osd_cull::frame {

namespace {

constexpr VkShaderStageFlags kGraphicsStages = VK_SHADER_STAGE_ALL_GRAPHICS;

shader::DrawConstants drawConstants(const Camera& camera, const RenderOptions& options) {
  shader::DrawConstants c{};
  const auto& t = options.tessellation;
  writeTessConstants(c, camera, t);
  c.flags = (options.debugColors ? shader::kFlagDebugColors : 0u) |
            (options.statusColors ? shader::kFlagStatusColors : 0u) |
            (options.frontFacesWinTies ? shader::kFlagFrontWinsTies : 0u) |
            (options.clampDepthToControlPoints ? 0u : shader::kFlagNoDepthClamp) |
            (options.patchTypeColors && !options.statusColors ? shader::kFlagPatchTypeColors : 0u);
  if (t.displaced == DisplacedTessellation::Ignore) c.flags |= shader::kFlagTessIgnoreDisplacement;
  if (t.displaced == DisplacedTessellation::PerPatch)
    c.flags |= shader::kFlagTessPerPatchDisplacement;
  return c;
}

void checkOptions(const vulkan::Context& context, const Camera& camera, const RenderTarget& target,
                  const RenderOptions& options) {
  const auto& t = options.tessellation;
  const uint32_t deviceMax = context.info().limits.maxTessellationGenerationLevel;
  if (t.maxLevel < 2 || t.maxLevel > deviceMax)
    throw Error("tessellation maxLevel " + std::to_string(t.maxLevel) + " is not in [2, " +
                std::to_string(deviceMax) + "]");
  if (t.mode == TessellationOptions::Mode::Uniform &&
      (t.uniformLevel < 1 || t.uniformLevel > t.maxLevel))
    throw Error("uniform tessellation level " + std::to_string(t.uniformLevel) + " is not in [1, " +
                std::to_string(t.maxLevel) + "]");
  if (t.mode == TessellationOptions::Mode::Adaptive && !(t.pixelsPerSegment > 0.0))
    throw Error("adaptive tessellation needs pixelsPerSegment > 0");
  if (camera.width != target.width() || camera.height != target.height())
    throw Error("camera viewport " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height) + " differs from the render target " +
                std::to_string(target.width()) + "x" + std::to_string(target.height()));
}

// The stages of a patch pipeline: vertex, control, evaluation, fragment. `bda`: the
// OSD_CULL_POINTS_BDA define (pointsByAddressDefine), `items`: an item buffer is written.
std::array<vulkan::ShaderSource, 4> patchShaders(PatchType type, bool displaced, const char* bda,
                                                 bool items) {
  const std::string points = type == PatchType::Bezier ? "16" : "20";
  std::vector<vulkan::ShaderDefine> defines = {{"PATCH_POINTS", points},
                                               {"OSD_CULL_POINTS_BDA", bda}};
  std::vector<vulkan::ShaderDefine> evalDefines = defines;
  // Only the displaced variant's control and evaluation stages have displacement code
  // (the edge levels' displacement term, displace.glsl); its control stage leaves fragment
  // depth unclamped (patch.tesc).
  if (displaced) evalDefines.push_back({"PATCH_DISPLACED", "1"});
  return {vulkan::ShaderSource{"patch/patch.vert", defines},
          vulkan::ShaderSource{"patch/patch.tesc", evalDefines},
          vulkan::ShaderSource{"patch/patch.tese", evalDefines},
          vulkan::ShaderSource{"patch/patch.frag", {{"ITEM_BUFFER", items ? "1" : "0"}}}};
}

// The stages of the triangle (occluder) pipeline: vertex, fragment.
std::array<vulkan::ShaderSource, 2> triangleShaders(bool items) {
  return {vulkan::ShaderSource{"mesh/triangle.vert", {}},
          vulkan::ShaderSource{"mesh/triangle.frag", {{"ITEM_BUFFER", items ? "1" : "0"}}}};
}

}  // namespace

std::vector<vulkan::ShaderVariant> rendererShaderVariants() {
  std::vector<vulkan::ShaderVariant> v;
  for (bool items : {false, true}) {
    for (PatchType type : {PatchType::Bezier, PatchType::Gregory})
      for (bool displaced : {false, true})
        for (const char* bda : {"0", "1"})
          for (const vulkan::ShaderSource& s : patchShaders(type, displaced, bda, items))
            v.push_back(vulkan::ShaderVariant::file(s));
    for (const vulkan::ShaderSource& s : triangleShaders(items))
      v.push_back(vulkan::ShaderVariant::file(s));
  }
  for (vulkan::ShaderVariant& s : tessLevelsPassShaderVariants()) v.push_back(std::move(s));
  return v;
}

Renderer::Renderer(vulkan::Context& context) : context_(context), statistics_(context, 1) {
  if (context.info().timestampValidBits > 0) timestamps_.emplace(context, 2);
  patchSetLayout_ = vulkan::createDescriptorSetLayout(context, patchSetBindings());
  meshSetLayout_ = vulkan::createDescriptorSetLayout(context, triangleMeshBindings());
  const VkDescriptorSetLayout p = patchSetLayout_.get();
  const VkDescriptorSetLayout m = meshSetLayout_.get();
  patchLayout_ = vulkan::createPipelineLayout(context, {&p, 1}, sizeof(shader::DrawConstants),
                                              kGraphicsStages);
  meshLayout_ = vulkan::createPipelineLayout(context, {&m, 1}, sizeof(shader::DrawConstants),
                                             kGraphicsStages);
  displacementSetLayout_ = vulkan::createDescriptorSetLayout(context, displacementSetBindings());
  const VkDescriptorSetLayout displaced[] = {p, displacementSetLayout_.get()};
  displacedLayout_ = vulkan::createPipelineLayout(context, displaced, sizeof(shader::DrawConstants),
                                                  kGraphicsStages);
}

void Renderer::describeTarget(vulkan::GraphicsPipelineDesc& d, const TargetFormat& format) {
  const bool items = format.items != VK_FORMAT_UNDEFINED;
  d.colorAttachments = items ? 2 : 1;
  d.samples = format.samples;
  d.subpass = format.subpass;
  if (format.dynamicRendering) {
    d.colorFormats = {format.color};
    if (items) d.colorFormats.push_back(format.items);
    d.depthFormat = format.depth;
  } else if (format.renderPass) {
    d.renderPass = format.renderPass;
  } else {
    auto& pass = referencePasses_[format];
    if (!pass) pass = createTargetRenderPass(context_, true, format);
    d.renderPass = pass.get();
  }
}

VkPipeline Renderer::patchPipeline(PatchType type, bool cullBackFaces, bool wireframe,
                                   bool mirrored, bool displaced, const TargetFormat& format) {
  auto& slot = patchPipelines_[{type, cullBackFaces, wireframe, mirrored, displaced, format}];
  if (slot) return slot.get();
  vulkan::GraphicsPipelineDesc d;
  for (const vulkan::ShaderSource& s : patchShaders(
           type, displaced, pointsByAddressDefine(context_), format.items != VK_FORMAT_UNDEFINED))
    d.stages.push_back({vulkan::shaderStageOf(s.path), vulkan::compileShader(s), {}});
  d.layout = displaced ? displacedLayout_.get() : patchLayout_.get();
  describeTarget(d, format);
  d.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  d.patchControlPoints = type == PatchType::Bezier ? kBezierPoints : kGregoryPoints;
  d.cullMode = cullBackFaces ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
  if (wireframe) {
    if (!context_.info().optional.fillModeNonSolid)
      throw Error("wireframe drawing needs the device feature fillModeNonSolid");
    d.polygonMode = VK_POLYGON_MODE_LINE;
  }
  // With the y-flipping projections of camera.h, triangles of a patch whose dP/du x dP/dv
  // faces the eye come out clockwise in framebuffer space; a mirroring model matrix
  // (instanceCamera() with a negative determinant) turns them counter-clockwise.
  d.frontFace = mirrored ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
  slot = vulkan::createGraphicsPipeline(context_, d);
  return slot.get();
}

VkPipeline Renderer::trianglePipeline(const TargetFormat& format) {
  auto& slot = trianglePipelines_[format];
  if (slot) return slot.get();
  vulkan::GraphicsPipelineDesc d;
  for (const vulkan::ShaderSource& s : triangleShaders(format.items != VK_FORMAT_UNDEFINED))
    d.stages.push_back({vulkan::shaderStageOf(s.path), vulkan::compileShader(s), {}});
  d.layout = meshLayout_.get();
  describeTarget(d, format);
  slot = vulkan::createGraphicsPipeline(context_, d);
  return slot.get();
}

void Renderer::beginPass(VkCommandBuffer cmd, RenderTarget& target,
                         const RenderOptions& options) const {
  if (!options.clear && !target.hasContents())
    throw Error("Renderer: RenderOptions::clear is false but the target was never drawn");
  if (openTarget_) throw Error("Renderer::beginPass: the previous pass was not ended");
  VkClearValue clears[3]{};
  clears[0].color = {{options.background.r, options.background.g, options.background.b, 1.0f}};
  if (target.hasItems()) {
    clears[1].color.uint32[0] = shader::kItemBackground;
    clears[2].depthStencil = {1.0f, 0};
  } else {
    clears[1].depthStencil = {1.0f, 0};
  }
  if (target.format().dynamicRendering) {
    beginRendering(context_, cmd, target, options.clear, clears);
  } else {
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = options.clear ? target.clearPass() : target.loadPass();
    begin.framebuffer = target.framebuffer();
    begin.renderArea = {{0, 0}, {target.width(), target.height()}};
    const bool appClears = !target.clearValues().empty();
    begin.clearValueCount = !options.clear ? 0
                            : appClears    ? static_cast<uint32_t>(target.clearValues().size())
                                           : (target.hasItems() ? 3u : 2u);
    begin.pClearValues = !options.clear ? nullptr
                         : appClears    ? target.clearValues().data()
                                        : clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  }
  const VkViewport viewport{0.0f, 0.0f, float(target.width()), float(target.height()), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {target.width(), target.height()}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  target.markDrawn();
  openTarget_ = &target;
  drawFormat_ = target.format();
}

void Renderer::endPass(VkCommandBuffer cmd) const {
  if (!openTarget_) throw Error("Renderer::endPass: no pass is open");
  if (openTarget_->format().dynamicRendering)
    endRendering(context_, cmd, *openTarget_);
  else
    vkCmdEndRenderPass(cmd);
  openTarget_ = nullptr;
}

void Renderer::recordOccluders(VkCommandBuffer cmd, const Camera& camera,
                               std::span<const GpuTriangleMesh* const> occluders) {
  if (occluders.empty()) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, trianglePipeline(drawFormat_));
  shader::DrawConstants c = drawConstants(camera, {});
  c.pointStride = 4;
  c.itemBase = shader::kItemOccluder;
  vkCmdPushConstants(cmd, meshLayout_.get(), kGraphicsStages, 0, sizeof(c), &c);
  for (const GpuTriangleMesh* mesh : occluders) {
    const VkDescriptorSet set = mesh->descriptorSet();
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, meshLayout_.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdBindIndexBuffer(cmd, mesh->indices().handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh->indexCount(), 1, 0, 0, 0);
  }
}

void Renderer::bindPatches(VkCommandBuffer cmd, const Camera& world, const PatchDraw& draw,
                           PatchType type, const RenderOptions& options) {
  const GpuPatchSet& gpu = *draw.gpu;
  const Camera camera = draw.model ? instanceCamera(world, *draw.model) : world;
  const GpuDisplacement* displacement = gpu.displacement();
  const VkPipelineLayout layout = displacement ? displacedLayout_.get() : patchLayout_.get();
  vkCmdBindPipeline(
      cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
      patchPipeline(type, draw.cullBackFaces.value_or(options.cullBackFaces), options.wireframe,
                    isMirrored(camera), displacement != nullptr, drawFormat_));
  const VkDescriptorSet sets[] = {draw.set ? draw.set : gpu.descriptorSet(),
                                  displacement ? displacement->descriptorSet() : VK_NULL_HANDLE};
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, displacement ? 2 : 1,
                          sets, 0, nullptr);
  RenderOptions effective = options;
  effective.tessellation = effectiveOptions(options.tessellation, gpu.hasTransitionEdges());
  shader::DrawConstants c = drawConstants(camera, effective);
  c.bezierCount = gpu.bezierCount();
  c.pointStride = gpu.pointStride();
  c.pointOffset = gpu.pointOffset();
  c.itemBase = draw.itemBase;
  if (draw.tessLevelSlot && usesTessLevelsPass(gpu, options.tessellation)) {
    if (*draw.tessLevelSlot >= gpu.tessLevelSlots())
      throw Error("Renderer: PatchDraw::tessLevelSlot " + std::to_string(*draw.tessLevelSlot) +
                  " of a set with " + std::to_string(gpu.tessLevelSlots()) + " level slots");
    c.flags |= shader::kFlagTessLevelsFromBuffer;
    c.levelBase = *draw.tessLevelSlot * gpu.patchCount();
  }
  vkCmdPushConstants(cmd, layout, kGraphicsStages, 0, sizeof(c), &c);
}

void Renderer::recordIndirect(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                              PatchType type, const vulkan::Buffer& commands, VkDeviceSize offset,
                              const vulkan::Buffer& count, VkDeviceSize countOffset,
                              uint32_t maxDraws, const RenderOptions& options) {
  if (!draw.gpu) throw Error("Renderer: PatchDraw without a GpuPatchSet");
  if (maxDraws == 0) return;
  vulkan::checkDrawIndirectCount(context_, maxDraws, "Renderer::recordIndirect");
  bindPatches(cmd, camera, draw, type, options);
  vkCmdDrawIndirectCount(cmd, commands.handle(), offset, count.handle(), countOffset, maxDraws,
                         sizeof(VkDrawIndirectCommand));
}

uint32_t Renderer::recordSlots(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                               PatchType type, uint32_t firstSlot, uint32_t count,
                               std::span<const uint32_t> vertexBounds,
                               const RenderOptions& options) {
  if (count == 0) return 0;
  bindPatches(cmd, camera, draw, type, options);
  const uint32_t points = type == PatchType::Bezier ? kBezierPoints : kGregoryPoints;
  std::vector<DrawChunk> chunks;
  if (!options.chunkDraws) {
    chunks.push_back({0, count});
  } else if (!vertexBounds.empty()) {
    chunks = planDrawChunks(vertexBounds, points);
  } else {
    const auto& t = options.tessellation;
    const uint32_t m = t.mode == TessellationOptions::Mode::Uniform
                           ? std::min(t.uniformLevel * 2, t.maxLevel)
                           : t.maxLevel;
    const std::vector<uint32_t> bounds(count, (m + 1) * (m + 1));
    chunks = planDrawChunks(bounds, points);
  }
  for (const DrawChunk& chunk : chunks)
    vkCmdDraw(cmd, chunk.count * points, 1, (firstSlot + chunk.first) * points, 0);
  return static_cast<uint32_t>(chunks.size());
}

void Renderer::recordTessLevels(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                                uint32_t slot, const RenderOptions& options) {
  if (!draw.gpu) throw Error("Renderer: PatchDraw without a GpuPatchSet");
  if (!usesTessLevelsPass(*draw.gpu, options.tessellation)) return;
  if (!tessLevels_) tessLevels_ = std::make_unique<TessLevelsPass>(context_);
  tessLevels_->record(cmd, camera, draw.model, *draw.gpu, slot, options.tessellation);
}

uint32_t Renderer::recordPatches(VkCommandBuffer cmd, const Camera& camera, const PatchDraw& draw,
                                 const RenderOptions& options) {
  if (!draw.gpu) throw Error("Renderer: PatchDraw without a GpuPatchSet");
  const GpuPatchSet& gpu = *draw.gpu;
  std::vector<uint32_t> bounds;
  if (draw.host) {
    if (draw.host->patchCount() != gpu.patchCount())
      throw Error("Renderer: host PatchSet has " + std::to_string(draw.host->patchCount()) +
                  " patches, the GpuPatchSet " + std::to_string(gpu.patchCount()));
    const GpuDisplacement* displacement = gpu.displacement();
    bounds = tessVertexBounds(
        *draw.host, camera.viewProjection(), glm::dvec2(camera.width, camera.height),
        options.tessellation,
        displacement ? displacement->edgeDisplacements() : std::span<const EdgeDisplacement>{});
  }
  const std::span<const uint32_t> all(bounds);
  const uint32_t nb = gpu.bezierCount();
  const uint32_t ng = gpu.gregoryCount();
  uint32_t draws = recordSlots(cmd, camera, draw, PatchType::Bezier, 0, nb,
                               bounds.empty() ? all : all.subspan(0, nb), options);
  draws += recordSlots(cmd, camera, draw, PatchType::Gregory, gpu.firstGregorySlot(), ng,
                       bounds.empty() ? all : all.subspan(nb, ng), options);
  return draws;
}

FrameStats Renderer::render(RenderTarget& target, const Camera& camera,
                            std::span<const PatchDraw> patches,
                            std::span<const GpuTriangleMesh* const> occluders,
                            const RenderOptions& options) {
  uint32_t patchesDrawn = 0;
  // Adaptive levels of undisplaced sets come from the levels pass: the given slot, else the
  // next free slot of the set (a set drawn more often than it has slots computes the rest
  // in its control shader).
  std::vector<PatchDraw> draws(patches.begin(), patches.end());
  std::map<const GpuPatchSet*, uint32_t> used;
  for (PatchDraw& d : draws) {
    if (!d.gpu || !usesTessLevelsPass(*d.gpu, options.tessellation)) continue;
    const uint32_t next = used[d.gpu]++;
    if (!d.tessLevelSlot && next < d.gpu->tessLevelSlots()) d.tessLevelSlot = next;
  }
  FrameStats stats = renderWith(
      target, camera, occluders, options,
      [&](VkCommandBuffer cmd) {
        for (const PatchDraw& d : draws)
          if (d.tessLevelSlot) recordTessLevels(cmd, camera, d, *d.tessLevelSlot, options);
      },
      [&](VkCommandBuffer cmd) {
        uint32_t calls = 0;
        for (const PatchDraw& d : draws) {
          calls += recordPatches(cmd, camera, d, options);
          patchesDrawn += d.gpu->patchCount();
        }
        return calls;
      });
  stats.patchesDrawn = patchesDrawn;
  return stats;
}

FrameStats Renderer::renderWith(RenderTarget& target, const Camera& camera,
                                std::span<const GpuTriangleMesh* const> occluders,
                                const RenderOptions& options,
                                const std::function<void(VkCommandBuffer)>& beforePass,
                                const std::function<uint32_t(VkCommandBuffer)>& recordPatchDraws) {
  checkOptions(context_, camera, target, options);
  FrameStats stats;
  const auto start = std::chrono::steady_clock::now();
  context_.submit([&](VkCommandBuffer cmd) {
    statistics_.reset(cmd);
    if (timestamps_) {
      timestamps_->reset(cmd);
      timestamps_->write(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0);
    }
    beforePass(cmd);
    beginPass(cmd, target, options);
    statistics_.begin(cmd);
    recordOccluders(cmd, camera, occluders);
    stats.drawCalls += recordPatchDraws(cmd);
    statistics_.end(cmd);
    endPass(cmd);
    if (timestamps_) timestamps_->write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 1);
  });
  stats.wallMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (timestamps_) stats.gpuMs = timestamps_->elapsedMs(0, 1);
  stats.statistics = statistics_.result();
  for (const GpuTriangleMesh* m : occluders) stats.occluderTriangles += m->indexCount() / 3;
  stats.drawCalls += static_cast<uint32_t>(occluders.size());
  return stats;
}

FrameStats Renderer::render(RenderTarget& target, const Camera& camera, const GpuPatchSet& patches,
                            const PatchSet* host, const RenderOptions& options) {
  const PatchDraw draw{&patches, host, 0};
  return render(target, camera, {&draw, 1}, {}, options);
}

}  // namespace osd_cull::frame
