#pragma once
/// \file compute_evaluator.h
/// \brief VkComputeEvaluator: stencil evaluation in a Vulkan compute shader, the EVALUATOR
/// of Osd::Mesh for this backend (like Osd::GLComputeEvaluator).

#include "osd_cull/error.h"
#include "osd_cull/osd/device_context.h"
#include "osd_cull/osd/stencil_table.h"

#include <opensubdiv/osd/bufferDescriptor.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace osd_cull::vulkan {
class ComputeProgram;
}

namespace osd_cull::osd {

using OpenSubdiv::Osd::BufferDescriptor;

/// \brief A vertex buffer as the stencil kernel sees it: a VkBuffer of `floats` floats and
/// the descriptor locating the vertices in it. An empty binding (null buffer) is skipped.
struct EvaluatorBinding {
  VkBuffer buffer = VK_NULL_HANDLE;
  size_t floats = 0;
  BufferDescriptor desc;
};

/// \brief Evaluates a VkStencilTable on the GPU: dst[i] = sum of weights * src[indices] for
/// every stencil i, vertices located by Osd::BufferDescriptor (offset, length, stride, in
/// floats), with optional du/dv outputs from limit stencils (shaders/osd/eval_stencils.comp).
///
/// It satisfies OpenSubdiv's evaluator concept: `Instantiatable`, Create (as called by
/// Osd::EvaluatorCacheT), static EvalStencils with and without first derivatives (the
/// forms Osd::Mesh and OpenSubdiv programs call) and static Synchronize. Second
/// derivatives are not implemented: Create throws when their descriptors are valid, and
/// the EvalStencils forms that take them do not exist (a compile-time error).
///
/// Work is submitted without waiting. `src` and `dst` may be the same buffer (Osd::Mesh
/// writes refined vertices after the control vertices), as long as no stencil reads a
/// vertex that the same evaluation writes — true of factorized Far stencil tables.
/// Buffers passed in must be VkVertexBuffer-like: `BindVBO(DeviceContext*)` returning a
/// VkBuffer of `GetNumVertices() * GetNumElements()` floats.
class VkComputeEvaluator {
 public:
  /// Tells Osd::Mesh to keep instances in an Osd::EvaluatorCacheT.
  using Instantiatable = bool;

  /// \brief An instance for these descriptors, owned by the caller (EvaluatorCacheT
  /// deletes it). Its kernel is compiled once per DeviceContext and element count.
  /// \throws osd_cull::Error when deviceContext is null or a descriptor is unusable.
  static VkComputeEvaluator* Create(BufferDescriptor const& srcDesc,
                                    BufferDescriptor const& dstDesc, BufferDescriptor const& duDesc,
                                    BufferDescriptor const& dvDesc, DeviceContext* deviceContext);
  /// \brief As above; duu/duv/dvv must be empty (second derivatives are not supported).
  static VkComputeEvaluator* Create(BufferDescriptor const& srcDesc,
                                    BufferDescriptor const& dstDesc, BufferDescriptor const& duDesc,
                                    BufferDescriptor const& dvDesc, BufferDescriptor const& duuDesc,
                                    BufferDescriptor const& duvDesc,
                                    BufferDescriptor const& dvvDesc, DeviceContext* deviceContext);

  /// \brief An evaluator for vertices of srcDesc.length floats; with derivative outputs
  /// when duDesc or dvDesc has a positive length.
  VkComputeEvaluator(DeviceContext& deviceContext, BufferDescriptor const& srcDesc,
                     BufferDescriptor const& dstDesc, BufferDescriptor const& duDesc = {},
                     BufferDescriptor const& dvDesc = {});
  VkComputeEvaluator(const VkComputeEvaluator&) = delete;
  VkComputeEvaluator& operator=(const VkComputeEvaluator&) = delete;
  ~VkComputeEvaluator();

  /// \brief Evaluates `stencilTable` from `srcBuffer` into `dstBuffer` (submitted, not
  /// waited for). Uses `instance` when given, else a temporary one for these descriptors.
  /// \returns true; errors throw osd_cull::Error (mismatched lengths, ranges outside a
  /// buffer, no DeviceContext).
  template <class SRC_BUFFER, class DST_BUFFER, class STENCIL_TABLE>
  static bool EvalStencils(SRC_BUFFER* srcBuffer, BufferDescriptor const& srcDesc,
                           DST_BUFFER* dstBuffer, BufferDescriptor const& dstDesc,
                           STENCIL_TABLE const* stencilTable, VkComputeEvaluator const* instance,
                           DeviceContext* deviceContext = nullptr) {
    if (instance)
      return instance->EvalStencils(srcBuffer, srcDesc, dstBuffer, dstDesc, stencilTable);
    const VkComputeEvaluator temporary(requireContext(deviceContext), srcDesc, dstDesc);
    return temporary.EvalStencils(srcBuffer, srcDesc, dstBuffer, dstDesc, stencilTable);
  }

  /// \brief The same with first derivatives: the table must hold du/dv weights (built
  /// from a Far::LimitStencilTable). A descriptor of length 0 skips that output.
  template <class SRC_BUFFER, class DST_BUFFER, class STENCIL_TABLE>
  static bool EvalStencils(SRC_BUFFER* srcBuffer, BufferDescriptor const& srcDesc,
                           DST_BUFFER* dstBuffer, BufferDescriptor const& dstDesc,
                           DST_BUFFER* duBuffer, BufferDescriptor const& duDesc,
                           DST_BUFFER* dvBuffer, BufferDescriptor const& dvDesc,
                           STENCIL_TABLE const* stencilTable, VkComputeEvaluator const* instance,
                           DeviceContext* deviceContext = nullptr) {
    if (instance)
      return instance->EvalStencils(srcBuffer, srcDesc, dstBuffer, dstDesc, duBuffer, duDesc,
                                    dvBuffer, dvDesc, stencilTable);
    const VkComputeEvaluator temporary(requireContext(deviceContext), srcDesc, dstDesc, duDesc,
                                       dvDesc);
    return temporary.EvalStencils(srcBuffer, srcDesc, dstBuffer, dstDesc, duBuffer, duDesc,
                                  dvBuffer, dvDesc, stencilTable);
  }

  /// \brief Member form of EvalStencils (this instance's kernel).
  template <class SRC_BUFFER, class DST_BUFFER, class STENCIL_TABLE>
  bool EvalStencils(SRC_BUFFER* srcBuffer, BufferDescriptor const& srcDesc, DST_BUFFER* dstBuffer,
                    BufferDescriptor const& dstDesc, STENCIL_TABLE const* stencilTable) const {
    return evalAndTrack(stencilTable, srcBuffer, srcDesc, dstBuffer, dstDesc,
                        static_cast<DST_BUFFER*>(nullptr), {}, static_cast<DST_BUFFER*>(nullptr),
                        {});
  }

  /// \brief Member form of EvalStencils with first derivatives.
  template <class SRC_BUFFER, class DST_BUFFER, class STENCIL_TABLE>
  bool EvalStencils(SRC_BUFFER* srcBuffer, BufferDescriptor const& srcDesc, DST_BUFFER* dstBuffer,
                    BufferDescriptor const& dstDesc, DST_BUFFER* duBuffer,
                    BufferDescriptor const& duDesc, DST_BUFFER* dvBuffer,
                    BufferDescriptor const& dvDesc, STENCIL_TABLE const* stencilTable) const {
    return evalAndTrack(stencilTable, srcBuffer, srcDesc, dstBuffer, dstDesc, duBuffer, duDesc,
                        dvBuffer, dvDesc);
  }

  /// \brief Waits until every evaluation submitted on `deviceContext` by any
  /// VkComputeEvaluator has finished (their fences; not vkDeviceWaitIdle, and later
  /// unrelated submissions are not waited for).
  static void Synchronize(DeviceContext* deviceContext);
  /// \brief Waits until this instance's own evaluations have finished.
  void synchronize() const;

  using Binding = EvaluatorBinding;

  /// \brief Records the evaluation of stencils [start, end) into `batch`, with barriers
  /// ordering it after earlier work on the queue and before later work. Checks every
  /// range first. For callers that combine it with other work in one submission.
  void record(Batch& batch, const VkStencilTable& table, const Binding& src, const Binding& dst,
              const Binding& du, const Binding& dv, int start, int end) const;
  /// \brief record() for all stencils in a submission of its own; returns its ticket.
  uint64_t submit(const VkStencilTable& table, const Binding& src, const Binding& dst,
                  const Binding& du = {}, const Binding& dv = {}) const;

  int length() const { return length_; }
  bool hasDerivatives() const { return derivatives_; }

 private:
  static DeviceContext& requireContext(DeviceContext* deviceContext);

  template <class BUFFER>
  Binding bind(BUFFER* buffer, BufferDescriptor const& desc) const {
    if (!buffer || desc.length <= 0) return {};
    return {buffer->BindVBO(&deviceContext_),
            static_cast<size_t>(buffer->GetNumVertices()) *
                static_cast<size_t>(buffer->GetNumElements()),
            desc};
  }
  template <class BUFFER>
  static void markUsed(BUFFER* buffer, uint64_t ticket) {
    if constexpr (requires { buffer->markUsed(ticket); })
      if (buffer) buffer->markUsed(ticket);
  }
  template <class STENCIL_TABLE, class SRC_BUFFER, class DST_BUFFER>
  bool evalAndTrack(STENCIL_TABLE const* table, SRC_BUFFER* src, BufferDescriptor const& srcDesc,
                    DST_BUFFER* dst, BufferDescriptor const& dstDesc, DST_BUFFER* du,
                    BufferDescriptor const& duDesc, DST_BUFFER* dv,
                    BufferDescriptor const& dvDesc) const {
    if (!table) throw Error("VkComputeEvaluator::EvalStencils: the stencil table is null");
    const uint64_t ticket =
        submit(*table, bind(src, srcDesc), bind(dst, dstDesc), bind(du, duDesc), bind(dv, dvDesc));
    markUsed(src, ticket);
    markUsed(dst, ticket);
    markUsed(du, ticket);
    markUsed(dv, ticket);
    return true;
  }

  DeviceContext& deviceContext_;
  int length_;
  bool derivatives_;
  std::shared_ptr<const vulkan::ComputeProgram> kernel_;
  mutable uint64_t lastTicket_ = 0;
};

}  // namespace osd_cull::osd
