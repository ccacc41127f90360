#include "osd_cull/osd/stencil_table.h"

#include "osd_cull/error.h"
#include "osd_cull/osd/storage.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace osd_cull::osd {

namespace Far = OpenSubdiv::Far;

VkStencilTable* VkStencilTable::Create(Far::StencilTable const* stencilTable,
                                       DeviceContext* deviceContext) {
  if (!stencilTable || !deviceContext)
    throw Error("VkStencilTable::Create: the stencil table or the DeviceContext is null");
  // Osd::Mesh deletes what Create returns: ownership leaves as a raw pointer by contract.
  return std::make_unique<VkStencilTable>(*deviceContext, *stencilTable).release();
}

VkStencilTable* VkStencilTable::Create(Far::LimitStencilTable const* stencilTable,
                                       DeviceContext* deviceContext) {
  if (!stencilTable || !deviceContext)
    throw Error("VkStencilTable::Create: the limit stencil table or the DeviceContext is null");
  return std::make_unique<VkStencilTable>(*deviceContext, *stencilTable).release();
}

VkStencilTable::VkStencilTable(DeviceContext& deviceContext, Far::StencilTable const& table)
    : deviceContext_(deviceContext) {
  load(table.GetSizes(), table.GetOffsets(), table.GetControlIndices(), table.GetWeights());
}

VkStencilTable::VkStencilTable(DeviceContext& deviceContext, Far::LimitStencilTable const& table)
    : deviceContext_(deviceContext) {
  load(table.GetSizes(), table.GetOffsets(), table.GetControlIndices(), table.GetWeights());
  const size_t entries = table.GetControlIndices().size();
  if (table.GetDuWeights().size() != entries || table.GetDvWeights().size() != entries)
    throw Error("VkStencilTable: the limit stencil table has " +
                std::to_string(table.GetDuWeights().size()) + " du and " +
                std::to_string(table.GetDvWeights().size()) + " dv weights for " +
                std::to_string(entries) + " entries (was it built without derivatives?)");
  vulkan::Context& context = deviceContext.context();
  duWeights_ = makeStorageBuffer<float>(context, table.GetDuWeights(), "VkStencilTable du weights");
  dvWeights_ = makeStorageBuffer<float>(context, table.GetDvWeights(), "VkStencilTable dv weights");
}

VkStencilTable::VkStencilTable(DeviceContext& deviceContext, std::span<const int> sizes,
                               std::span<const int> offsets, std::span<const int> indices,
                               std::span<const float> weights)
    : deviceContext_(deviceContext) {
  load(sizes, offsets, indices, weights);
}

VkStencilTable::VkStencilTable(DeviceContext& deviceContext, std::span<const int> sizes,
                               std::span<const int> offsets, std::span<const int> indices,
                               std::span<const double> weights)
    : deviceContext_(deviceContext) {
  const std::vector<float> rounded(weights.begin(), weights.end());
  load(sizes, offsets, indices, rounded);
}

VkStencilTable::~VkStencilTable() {
  try {
    deviceContext_.wait(lastUse_);
  } catch (...) {
    // A destructor cannot report; a failed wait means the device is lost.
  }
}

void VkStencilTable::load(std::span<const int> sizes, std::span<const int> offsets,
                          std::span<const int> indices, std::span<const float> weights) {
  if (sizes.size() != offsets.size())
    throw Error("VkStencilTable: " + std::to_string(sizes.size()) + " sizes but " +
                std::to_string(offsets.size()) + " offsets");
  if (indices.size() != weights.size())
    throw Error("VkStencilTable: " + std::to_string(indices.size()) + " indices but " +
                std::to_string(weights.size()) + " weights");
  for (size_t s = 0; s < sizes.size(); ++s)
    if (sizes[s] < 0 || offsets[s] < 0 ||
        static_cast<size_t>(offsets[s]) + static_cast<size_t>(sizes[s]) > indices.size())
      throw Error("VkStencilTable: stencil " + std::to_string(s) + " (offset " +
                  std::to_string(offsets[s]) + ", size " + std::to_string(sizes[s]) +
                  ") lies outside the " + std::to_string(indices.size()) + " entries");
  int maxIndex = -1;
  for (size_t e = 0; e < indices.size(); ++e) {
    if (indices[e] < 0)
      throw Error("VkStencilTable: entry " + std::to_string(e) + " has the negative index " +
                  std::to_string(indices[e]));
    maxIndex = std::max(maxIndex, indices[e]);
  }
  numStencils_ = static_cast<int>(sizes.size());
  numSourceVertices_ = maxIndex + 1;
  vulkan::Context& context = deviceContext_.context();
  sizes_ = makeStorageBuffer(context, sizes, "VkStencilTable sizes");
  offsets_ = makeStorageBuffer(context, offsets, "VkStencilTable offsets");
  indices_ = makeStorageBuffer(context, indices, "VkStencilTable indices");
  weights_ = makeStorageBuffer(context, weights, "VkStencilTable weights");
}

void VkStencilTable::markUsed(uint64_t ticket) const { lastUse_ = std::max(lastUse_, ticket); }

}  // namespace osd_cull::osd
