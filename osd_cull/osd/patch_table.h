#pragma once
/// \file patch_table.h
/// \brief VkPatchTable: a Far::PatchTable's patch arrays, control-point indices and patch
/// params in Vulkan buffers (the PATCH_TABLE of Osd::Mesh, like Osd::GLPatchTable).

#include "osd_cull/osd/device_context.h"
#include "osd_cull/vk/buffer.h"

#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/osd/types.h>

#include <cstddef>
#include <vector>

namespace osd_cull::osd {

/// \brief Device copy of a patch table, laid out as Osd::CpuPatchTable lays it out:
/// - patch arrays (host side): descriptor, patch count, first index, first patch;
/// - index buffer: the control-point indices of every patch, array after array (int32);
/// - patch-param buffer: per patch an Osd::PatchParam {faceIndex, patchBits, sharpness};
/// - the same for the varying patches and every face-varying channel.
/// Buffers are storage buffers; index buffers are also usable as VK_INDEX_TYPE_UINT32.
class VkPatchTable {
 public:
  /// \brief What Osd::Mesh::BindVertexBuffer returns for this backend.
  using VertexBufferBinding = VkBuffer;

  /// \brief Device copy of `farPatchTable`, owned by the caller (Osd::Mesh deletes it).
  /// \throws osd_cull::Error when an argument is null or a buffer exceeds the device's
  /// storage range.
  static VkPatchTable* Create(OpenSubdiv::Far::PatchTable const* farPatchTable,
                              DeviceContext* deviceContext);

  VkPatchTable(DeviceContext& deviceContext, OpenSubdiv::Far::PatchTable const& farPatchTable);
  VkPatchTable(const VkPatchTable&) = delete;
  VkPatchTable& operator=(const VkPatchTable&) = delete;

  const OpenSubdiv::Osd::PatchArrayVector& GetPatchArrays() const { return patches_.arrays; }
  VkBuffer GetPatchIndexBuffer() const { return patches_.indices.handle(); }
  VkBuffer GetPatchParamBuffer() const { return patches_.params.handle(); }
  size_t GetPatchIndexSize() const { return patches_.indexCount; }
  size_t GetPatchParamSize() const { return patches_.paramCount; }

  const OpenSubdiv::Osd::PatchArrayVector& GetVaryingPatchArrays() const { return varying_.arrays; }
  VkBuffer GetVaryingPatchIndexBuffer() const { return varying_.indices.handle(); }
  size_t GetVaryingPatchIndexSize() const { return varying_.indexCount; }

  int GetNumFVarChannels() const { return static_cast<int>(fvar_.size()); }
  const OpenSubdiv::Osd::PatchArrayVector& GetFVarPatchArrays(int channel = 0) const {
    return fvar_.at(static_cast<size_t>(channel)).arrays;
  }
  VkBuffer GetFVarPatchIndexBuffer(int channel = 0) const {
    return fvar_.at(static_cast<size_t>(channel)).indices.handle();
  }
  VkBuffer GetFVarPatchParamBuffer(int channel = 0) const {
    return fvar_.at(static_cast<size_t>(channel)).params.handle();
  }

  /// \brief The buffer objects (for descriptor writes and read-backs).
  const vulkan::Buffer& patchIndexBuffer() const { return patches_.indices; }
  const vulkan::Buffer& patchParamBuffer() const { return patches_.params; }
  const vulkan::Buffer& varyingPatchIndexBuffer() const { return varying_.indices; }

 private:
  struct Patches {
    OpenSubdiv::Osd::PatchArrayVector arrays;
    vulkan::Buffer indices;
    vulkan::Buffer params;  // empty for varying patches
    size_t indexCount = 0;
    size_t paramCount = 0;
  };
  Patches patches_;
  Patches varying_;
  std::vector<Patches> fvar_;
};

}  // namespace osd_cull::osd
