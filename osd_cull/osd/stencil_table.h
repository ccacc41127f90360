#pragma once
/// \file stencil_table.h
/// \brief VkStencilTable: a Far::StencilTable in Vulkan storage buffers (the STENCIL_TABLE
/// of Osd::Mesh for this backend, like Osd::GLStencilTableSSBO).

#include "osd_cull/osd/device_context.h"
#include "osd_cull/vk/buffer.h"

#include <opensubdiv/far/stencilTable.h>

#include <cstdint>
#include <span>

namespace osd_cull::osd {

/// \brief Stencils in device buffers: per stencil its size and offset, per entry the
/// source vertex index and float weight (OpenSubdiv's layout and precision). Limit
/// stencil tables also carry du and dv weights.
///
/// Any compressed-row matrix of that shape can be loaded from raw arrays, e.g. the
/// cage → patch control point matrix (osd_cull/patch/point_matrix.h); double weights are
/// rounded to float.
class VkStencilTable {
 public:
  /// \brief Device copy of `stencilTable`, owned by the caller (Osd::Mesh deletes it).
  /// \throws osd_cull::Error when an argument is null or a buffer exceeds the device's
  /// storage range.
  static VkStencilTable* Create(OpenSubdiv::Far::StencilTable const* stencilTable,
                                DeviceContext* deviceContext);
  /// \brief Device copy of a limit stencil table, with du and dv weights.
  static VkStencilTable* Create(OpenSubdiv::Far::LimitStencilTable const* stencilTable,
                                DeviceContext* deviceContext);

  VkStencilTable(DeviceContext& deviceContext, OpenSubdiv::Far::StencilTable const& stencilTable);
  VkStencilTable(DeviceContext& deviceContext,
                 OpenSubdiv::Far::LimitStencilTable const& stencilTable);
  /// \brief From raw compressed rows: stencil s has `sizes[s]` entries starting at
  /// `offsets[s]` in `indices` and `weights`.
  /// \throws osd_cull::Error when the arrays disagree (lengths, a row beyond the entries,
  /// a negative index).
  VkStencilTable(DeviceContext& deviceContext, std::span<const int> sizes,
                 std::span<const int> offsets, std::span<const int> indices,
                 std::span<const float> weights);
  /// \brief The same with double weights, rounded to float.
  VkStencilTable(DeviceContext& deviceContext, std::span<const int> sizes,
                 std::span<const int> offsets, std::span<const int> indices,
                 std::span<const double> weights);
  VkStencilTable(const VkStencilTable&) = delete;
  VkStencilTable& operator=(const VkStencilTable&) = delete;
  /// \brief Waits for the submissions that read the table, then frees it.
  ~VkStencilTable();

  int GetNumStencils() const { return numStencils_; }
  /// \brief Source vertices the stencils read: 1 + the largest index (0 when empty).
  int GetNumSourceVertices() const { return numSourceVertices_; }
  bool HasDerivatives() const { return static_cast<bool>(duWeights_); }

  const vulkan::Buffer& GetSizesBuffer() const { return sizes_; }
  const vulkan::Buffer& GetOffsetsBuffer() const { return offsets_; }
  const vulkan::Buffer& GetIndicesBuffer() const { return indices_; }
  const vulkan::Buffer& GetWeightsBuffer() const { return weights_; }
  /// \brief du weights (empty buffer unless built from a limit stencil table).
  const vulkan::Buffer& GetDuWeightsBuffer() const { return duWeights_; }
  /// \brief dv weights (empty buffer unless built from a limit stencil table).
  const vulkan::Buffer& GetDvWeightsBuffer() const { return dvWeights_; }

  DeviceContext& deviceContext() const { return deviceContext_; }
  /// \brief Notes that submission `ticket` reads the table; the destructor waits for it.
  void markUsed(uint64_t ticket) const;

 private:
  void load(std::span<const int> sizes, std::span<const int> offsets, std::span<const int> indices,
            std::span<const float> weights);

  DeviceContext& deviceContext_;
  int numStencils_ = 0;
  int numSourceVertices_ = 0;
  vulkan::Buffer sizes_;
  vulkan::Buffer offsets_;
  vulkan::Buffer indices_;
  vulkan::Buffer weights_;
  vulkan::Buffer duWeights_;
  vulkan::Buffer dvWeights_;
  mutable uint64_t lastUse_ = 0;
};

}  // namespace osd_cull::osd
