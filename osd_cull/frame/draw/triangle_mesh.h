#pragma once
/// \file triangle_mesh.h
/// \brief Triangle meshes drawn as occluders (walls, ground) next to patches.

#include "osd_cull/vk/buffer.h"
#include "osd_cull/vk/descriptors.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace osd_cull::vulkan {
class Context;
}

namespace osd_cull::frame {

/// \brief An indexed triangle mesh (three indices per triangle).
struct TriangleMesh {
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> indices;
};

/// \brief An axis-aligned box as 12 triangles (an opaque wall when thin).
TriangleMesh boxMesh(const glm::dvec3& lo, const glm::dvec3& hi);

/// \brief A quad with corners a, b, c, d (in order) as two triangles.
TriangleMesh quadMesh(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d);

/// \brief Device copy of a TriangleMesh: positions as float x, y, z, 1 and 32-bit indices.
class GpuTriangleMesh {
 public:
  /// \throws osd_cull::Error for an empty mesh, an index count not divisible by three or an
  /// index out of range.
  GpuTriangleMesh(vulkan::Context& context, const TriangleMesh& mesh);
  const vulkan::Buffer& positions() const { return positions_; }
  const vulkan::Buffer& indices() const { return indices_; }
  uint32_t indexCount() const { return indexCount_; }
  /// \brief A descriptor set with the positions at binding 0 (triangleMeshBindings()).
  VkDescriptorSet descriptorSet() const { return set_; }

 private:
  vulkan::Buffer positions_;
  vulkan::Buffer indices_;
  uint32_t indexCount_ = 0;
  vulkan::UniqueDescriptorSetLayout setLayout_;
  std::unique_ptr<vulkan::DescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

/// \brief The descriptor bindings of a triangle mesh (positions at binding 0).
std::span<const vulkan::DescriptorBinding> triangleMeshBindings();

}  // namespace osd_cull::frame
