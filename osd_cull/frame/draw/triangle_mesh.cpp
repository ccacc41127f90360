#include "osd_cull/frame/draw/triangle_mesh.h"

#include "osd_cull/error.h"
#include "osd_cull/frame/draw/gpu_patch_set.h"
#include "osd_cull/vk/context.h"
#include "osd_cull/vk/transfer.h"

namespace osd_cull::frame {

std::span<const vulkan::DescriptorBinding> triangleMeshBindings() {
  static const vulkan::DescriptorBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_ALL}};
  return bindings;
}

TriangleMesh boxMesh(const glm::dvec3& lo, const glm::dvec3& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Outward-facing (counter-clockwise seen from outside).
  const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
  return m;
}

TriangleMesh quadMesh(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d) {
  return {{a, b, c, d}, {0, 1, 2, 0, 2, 3}};
}

GpuTriangleMesh::GpuTriangleMesh(vulkan::Context& context, const TriangleMesh& mesh)
    : indexCount_(static_cast<uint32_t>(mesh.indices.size())) {
  if (mesh.positions.empty() || mesh.indices.empty() || mesh.indices.size() % 3 != 0)
    throw Error("GpuTriangleMesh: need vertices and a multiple of three indices (got " +
                std::to_string(mesh.positions.size()) + " vertices, " +
                std::to_string(mesh.indices.size()) + " indices)");
  for (uint32_t i : mesh.indices)
    if (i >= mesh.positions.size())
      throw Error("GpuTriangleMesh: index " + std::to_string(i) + " out of range (" +
                  std::to_string(mesh.positions.size()) + " vertices)");
  const std::vector<float> packed = packPoints(mesh.positions);
  positions_ =
      vulkan::Buffer(context, packed.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  vulkan::upload<float>(context, positions_, packed);
  indices_ =
      vulkan::Buffer(context, mesh.indices.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  vulkan::upload<uint32_t>(context, indices_, mesh.indices);
  setLayout_ = vulkan::createDescriptorSetLayout(context, triangleMeshBindings());
  pool_ = std::make_unique<vulkan::DescriptorPool>(context, 1, triangleMeshBindings());
  set_ = pool_->allocate(setLayout_.get());
  vulkan::DescriptorWriter().buffer(0, positions_).update(context.device(), set_);
}

}  // namespace osd_cull::frame
