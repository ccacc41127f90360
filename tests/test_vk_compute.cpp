// Compute smoke test: a shader with a push constant, a specialization constant and two
// storage buffers runs, its results are exact, and the queries count it.
#include "osd_cull/error.h"
#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/commands.h"
#include "osd_cull/vk/descriptors.h"
#include "osd_cull/vk/glsl/runtime_compiler.h"
#include "osd_cull/vk/pipeline.h"
#include "osd_cull/vk/query.h"
#include "osd_cull/vk/transfer.h"
#include "support/vk_test_context.h"

#include <gtest/gtest.h>

namespace osd_cull {
namespace {

using test::VkTest;

constexpr const char* kAxpy = R"(#version 450
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOffset = 0;
layout(push_constant) uniform Push { uint a; uint count; } pc;
layout(std430, binding = 0) readonly buffer X { uint x[]; };
layout(std430, binding = 1) buffer Y { uint y[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) y[i] = pc.a * x[i] + y[i] + kOffset;
}
)";

struct Push {
  uint32_t a;
  uint32_t count;
};

TEST_F(VkTest, ComputeAxpyProducesExactValuesAndIsCounted) {
  constexpr uint32_t n = 1000;  // not a multiple of the group size
  std::vector<uint32_t> x(n), y(n);
  for (uint32_t i = 0; i < n; ++i) {
    x[i] = i;
    y[i] = 3 * i + 1;
  }
  vulkan::Buffer bx(context(), n * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::Buffer by(context(), n * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<uint32_t>(context(), bx, x);
  vulkan::upload<uint32_t>(context(), by, y);

  const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  auto setLayout = vulkan::createDescriptorSetLayout(context(), bindings);
  const VkDescriptorSetLayout sl = setLayout.get();
  auto layout =
      vulkan::createPipelineLayout(context(), {&sl, 1}, sizeof(Push), VK_SHADER_STAGE_COMPUTE_BIT);
  vulkan::SpecializationConstants constants;
  constants.set(0, uint32_t{5});
  auto spirv = vulkan::glsl::compileGlsl(kAxpy, "test/axpy.comp", VK_SHADER_STAGE_COMPUTE_BIT);
  auto pipeline = vulkan::createComputePipeline(context(), layout.get(), spirv, constants);
  vulkan::DescriptorPool pool(context(), 1, bindings);
  VkDescriptorSet set = pool.allocate(sl);
  vulkan::DescriptorWriter().buffer(0, bx).buffer(1, by).update(context().device(), set);

  vulkan::PipelineStatisticsQuery stats(context());
  const Push push{7, n};
  context().submit([&](VkCommandBuffer cmd) {
    stats.reset(cmd);
    stats.begin(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &set, 0,
                            nullptr);
    vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, vulkan::groupCount(n, 64), 1, 1);
    stats.end(cmd);
  });

  const auto out = vulkan::readback<uint32_t>(context(), by);
  ASSERT_EQ(out.size(), n);
  for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(out[i], 7 * i + 3 * i + 1 + 5) << "element " << i;
  EXPECT_EQ(stats.result().computeShaderInvocations, vulkan::groupCount(n, 64) * 64u);
}

TEST_F(VkTest, TimestampsAreOrderedAndNonNegative) {
  vulkan::TimestampQuery timestamps(context(), 2);
  vulkan::Buffer buffer(context(), 1 << 20, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  context().submit([&](VkCommandBuffer cmd) {
    timestamps.reset(cmd);
    timestamps.write(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0);
    vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, 42);
    timestamps.write(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 1);
  });
  const double ms = timestamps.elapsedMs(0, 1);
  EXPECT_GE(ms, 0.0);
  EXPECT_LT(ms, 10000.0);
  EXPECT_EQ(vulkan::readback<uint32_t>(context(), buffer)[12345], 42u);
}

TEST_F(VkTest, ComputeProgramRefusesAShaderThatIsNotEmbedded) {
  const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  EXPECT_THROW(vulkan::ComputeProgram(context(), {"no/such/file.comp", {}}, bindings, 8), Error);
}

}  // namespace
}  // namespace osd_cull
