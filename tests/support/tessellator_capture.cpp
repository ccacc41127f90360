#include "support/tessellator_capture.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/draw/render_target.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/glsl/runtime_compiler.h"
#include "osd_cull/vk/pipeline.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osd_cull::test {
namespace {

constexpr uint32_t kMaxTriangles = 20000;

struct Push {
  glm::vec4 lo;
  glm::vec4 hi;
};

const char* kVertex = R"(#version 450
void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }
)";

const char* kControl = R"(#version 450
layout(vertices = 1) out;
layout(push_constant) uniform Push { vec4 lo; vec4 hi; } pc;
layout(location = 0) patch out vec4 tcLo;
layout(location = 1) patch out vec4 tcHi;
void main() {
  vec4 outer = pc.lo + pc.hi;
  gl_TessLevelOuter[0] = outer[0];
  gl_TessLevelOuter[1] = outer[1];
  gl_TessLevelOuter[2] = outer[2];
  gl_TessLevelOuter[3] = outer[3];
  gl_TessLevelInner[0] = (outer[1] + outer[3]) * 0.5;
  gl_TessLevelInner[1] = (outer[0] + outer[2]) * 0.5;
  tcLo = pc.lo;
  tcHi = pc.hi;
}
)";

// The parameterization of shaders/patch/patch.tese (transition-edge remap included).
const char* kEvaluation = R"(#version 450
layout(quads, equal_spacing, ccw) in;
layout(location = 0) patch in vec4 tcLo;
layout(location = 1) patch in vec4 tcHi;
layout(location = 0) out vec2 teUv;
float transitionSplit(float t, float lo, float hi) {
  float ti = round(t * (lo + hi));
  return ti <= lo ? (ti / lo) * 0.5 : ((ti - lo) / hi) * 0.5 + 0.5;
}
void main() {
  vec2 p = gl_TessCoord.xy;
  vec2 uv = p;
  if (p.x == 0.0 && tcHi[0] > 0.0) uv.y = transitionSplit(p.y, tcLo[0], tcHi[0]);
  else if (p.y == 0.0 && tcHi[1] > 0.0) uv.x = transitionSplit(p.x, tcLo[1], tcHi[1]);
  else if (p.x == 1.0 && tcHi[2] > 0.0) uv.y = transitionSplit(p.y, tcLo[2], tcHi[2]);
  else if (p.y == 1.0 && tcHi[3] > 0.0) uv.x = transitionSplit(p.x, tcLo[3], tcHi[3]);
  teUv = uv;
  gl_Position = vec4(uv * 2.0 - 1.0, 0.5, 1.0);
}
)";

const char* kGeometry = R"(#version 450
layout(triangles) in;
layout(points, max_vertices = 1) out;
layout(location = 0) in vec2 teUv[];
layout(std430, set = 0, binding = 0) buffer Out { uint count; uint pad; vec2 corners[]; };
void main() {
  uint i = atomicAdd(count, 1u);
  if (i < MAX_TRIANGLES) {
    corners[3u * i + 0u] = teUv[0];
    corners[3u * i + 1u] = teUv[1];
    corners[3u * i + 2u] = teUv[2];
  }
}
)";

double l1(const glm::dvec2& d) { return std::abs(d.x) + std::abs(d.y); }

}  // namespace

struct TessellatorCapture::Impl {
  vulkan::Context& context;
  frame::RenderTarget target;
  vulkan::UniqueRenderPass pass;
  vulkan::Buffer out;
  vulkan::UniqueDescriptorSetLayout setLayout;
  vulkan::UniquePipelineLayout layout;
  vulkan::UniquePipeline pipeline;
  std::unique_ptr<vulkan::DescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;

  explicit Impl(vulkan::Context& c)
      : context(c),
        target(c, 8, 8),
        pass(frame::createTargetRenderPass(c, true)),
        out(c, 8 + size_t{kMaxTriangles} * 3 * 8,
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            vulkan::MemoryUse::Readback) {}
};

TessellatorCapture::TessellatorCapture(vulkan::Context& context)
    : impl_(std::make_unique<Impl>(context)) {
  if (!context.info().optional.geometryShader)
    throw Error("TessellatorCapture needs the geometryShader feature");
  const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_GEOMETRY_BIT}};
  impl_->setLayout = vulkan::createDescriptorSetLayout(context, bindings);
  const VkDescriptorSetLayout l = impl_->setLayout.get();
  impl_->layout = vulkan::createPipelineLayout(context, {&l, 1}, sizeof(Push),
                                               VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT);
  vulkan::GraphicsPipelineDesc d;
  const std::string geometry = std::string(kGeometry).replace(
      std::string(kGeometry).find("MAX_TRIANGLES"), 13, std::to_string(kMaxTriangles) + "u");
  d.stages.push_back(
      {VK_SHADER_STAGE_VERTEX_BIT,
       vulkan::glsl::compileGlsl(kVertex, "capture.vert", VK_SHADER_STAGE_VERTEX_BIT),
       {}});
  d.stages.push_back({VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT,
                      vulkan::glsl::compileGlsl(kControl, "capture.tesc",
                                                VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT),
                      {}});
  d.stages.push_back({VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT,
                      vulkan::glsl::compileGlsl(kEvaluation, "capture.tese",
                                                VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT),
                      {}});
  d.stages.push_back(
      {VK_SHADER_STAGE_GEOMETRY_BIT,
       vulkan::glsl::compileGlsl(geometry, "capture.geom", VK_SHADER_STAGE_GEOMETRY_BIT),
       {}});
  d.layout = impl_->layout.get();
  d.renderPass = impl_->pass.get();
  d.colorAttachments = 2;
  d.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  d.patchControlPoints = 1;
  impl_->pipeline = vulkan::createGraphicsPipeline(context, d);
  impl_->pool = std::make_unique<vulkan::DescriptorPool>(context, 1, bindings);
  impl_->set = impl_->pool->allocate(impl_->setLayout.get());
  vulkan::DescriptorWriter().buffer(0, impl_->out).update(context.device(), impl_->set);
}

TessellatorCapture::~TessellatorCapture() = default;

std::vector<ParamTriangle> TessellatorCapture::capture(const bound::QuadTessLevels& levels) {
  Impl& m = *impl_;
  Push push{};
  for (int e = 0; e < 4; ++e) {
    push.lo[e] = static_cast<float>(levels.lo[e]);
    push.hi[e] = static_cast<float>(levels.hi[e]);
  }
  m.context.submit([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, m.out.handle(), 0, 8, 0);
    vulkan::memoryBarrier(cmd, vulkan::scope::kTransferWrite,
                          {VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT});
    VkClearValue clears[3] = {};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = m.pass.get();
    begin.framebuffer = m.target.framebuffer();
    begin.renderArea.extent = {m.target.width(), m.target.height()};
    begin.clearValueCount = 3;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport{0.0f, 0.0f, float(m.target.width()), float(m.target.height()),
                              0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {m.target.width(), m.target.height()}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.layout.get(), 0, 1, &m.set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, m.layout.get(), VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 1, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    vulkan::memoryBarrier(cmd, {VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                          vulkan::scope::kHostRead);
  });
  const auto words = m.out.mappedAs<uint32_t>();
  const uint32_t count = words[0];
  if (count > kMaxTriangles)
    throw Error("TessellatorCapture: " + std::to_string(count) + " triangles, more than " +
                std::to_string(kMaxTriangles));
  const auto floats = m.out.mappedAs<float>().subspan(2);
  std::vector<ParamTriangle> triangles(count);
  for (uint32_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k)
      triangles[t][k] = glm::dvec2(floats[6 * t + 2 * k], floats[6 * t + 2 * k + 1]);
  return triangles;
}

bound::TriangleShape measuredShape(const std::vector<ParamTriangle>& triangles) {
  bound::TriangleShape s;
  s.minEdge = std::numeric_limits<double>::infinity();
  for (const ParamTriangle& t : triangles) {
    double bestPhi = std::numeric_limits<double>::infinity(), bestPsi = 0.0;
    for (int i = 0; i < 3; ++i) {
      const glm::dvec2 d1 = t[(i + 1) % 3] - t[i], d2 = t[(i + 2) % 3] - t[i];
      const double area2 = std::abs(d1.x * d2.y - d1.y * d2.x);
      const double a = l1(d1), b = l1(d2);
      s.minEdge = std::min(s.minEdge, a);
      if (!(area2 > 0.0)) continue;
      const double kappa = a * b / area2;
      if (kappa * (a + b) < bestPhi) bestPhi = kappa * (a + b), bestPsi = kappa * a * b;
    }
    s.phi = std::max(s.phi, bestPhi);
    s.psi = std::max(s.psi, bestPsi);
  }
  return s;
}

}  // namespace osd_cull::test
