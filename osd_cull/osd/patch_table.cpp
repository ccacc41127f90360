#include "osd_cull/osd/patch_table.h"

#include "osd_cull/error.h"
#include "osd_cull/osd/storage.h"

#include <opensubdiv/osd/cpuPatchTable.h>

#include <memory>
#include <span>

namespace osd_cull::osd {
namespace {

namespace Osd = OpenSubdiv::Osd;

static_assert(sizeof(Osd::PatchParam) == 12, "Osd::PatchParam is three 32-bit words");

// Index and param arrays are storage buffers, and index buffers for indexed draws.
template <class T>
vulkan::Buffer patchBuffer(vulkan::Context& context, std::span<const T> values, const char* what) {
  return makeStorageBuffer(context, values, what, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
}

template <class T>
std::span<const T> arrayOf(const T* data, size_t count) {
  return data ? std::span<const T>(data, count) : std::span<const T>();
}

}  // namespace

VkPatchTable* VkPatchTable::Create(OpenSubdiv::Far::PatchTable const* farPatchTable,
                                   DeviceContext* deviceContext) {
  if (!farPatchTable || !deviceContext)
    throw Error("VkPatchTable::Create: the patch table or the DeviceContext is null");
  // Osd::Mesh deletes what Create returns: ownership leaves as a raw pointer by contract.
  return std::make_unique<VkPatchTable>(*deviceContext, *farPatchTable).release();
}

VkPatchTable::VkPatchTable(DeviceContext& deviceContext,
                           OpenSubdiv::Far::PatchTable const& farPatchTable) {
  // OpenSubdiv's own CPU layout (arrays, indices, params with sharpness), as GLPatchTable
  // builds its buffers from it.
  const Osd::CpuPatchTable cpu(&farPatchTable);
  vulkan::Context& context = deviceContext.context();
  const size_t arrayCount = cpu.GetNumPatchArrays();

  const auto arrays = arrayOf(cpu.GetPatchArrayBuffer(), arrayCount);
  patches_.arrays.assign(arrays.begin(), arrays.end());
  patches_.indexCount = cpu.GetPatchIndexSize();
  patches_.paramCount = cpu.GetPatchParamSize();
  patches_.indices = patchBuffer(context, arrayOf(cpu.GetPatchIndexBuffer(), patches_.indexCount),
                                 "VkPatchTable indices");
  patches_.params = patchBuffer(context, arrayOf(cpu.GetPatchParamBuffer(), patches_.paramCount),
                                "VkPatchTable patch params");

  const auto varyingArrays = arrayOf(cpu.GetVaryingPatchArrayBuffer(), arrayCount);
  varying_.arrays.assign(varyingArrays.begin(), varyingArrays.end());
  varying_.indexCount = cpu.GetVaryingPatchIndexSize();
  varying_.indices =
      patchBuffer(context, arrayOf(cpu.GetVaryingPatchIndexBuffer(), varying_.indexCount),
                  "VkPatchTable varying indices");

  for (int channel = 0; channel < cpu.GetNumFVarChannels(); ++channel) {
    Patches fvar;
    const auto fvarArrays = arrayOf(cpu.GetFVarPatchArrayBuffer(channel), arrayCount);
    fvar.arrays.assign(fvarArrays.begin(), fvarArrays.end());
    fvar.indexCount = cpu.GetFVarPatchIndexSize(channel);
    fvar.paramCount = cpu.GetFVarPatchParamSize(channel);
    fvar.indices =
        patchBuffer(context, arrayOf(cpu.GetFVarPatchIndexBuffer(channel), fvar.indexCount),
                    "VkPatchTable face-varying indices");
    fvar.params =
        patchBuffer(context, arrayOf(cpu.GetFVarPatchParamBuffer(channel), fvar.paramCount),
                    "VkPatchTable face-varying patch params");
    fvar_.push_back(std::move(fvar));
  }
}

}  // namespace osd_cull::osd
