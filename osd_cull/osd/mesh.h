#pragma once
/// \file mesh.h
/// \brief The Vulkan backend plugged into OpenSubdiv's Osd::Mesh.
///
/// \code
///   osd_cull::osd::DeviceContext device(vkContext);
///   osd_cull::osd::VkEvaluatorCache evaluators;
///   osd_cull::osd::VkMesh mesh(refiner.release(), 3, 0, /*level*/ 2, bits, &evaluators, &device);
///   mesh.UpdateVertexBuffer(cage, 0, cageVertexCount);
///   mesh.Refine();       // stencils evaluated by a compute shader, not waited for
///   mesh.Synchronize();  // waits for the evaluation's fence
///   VkBuffer vertices = mesh.BindVertexBuffer();
/// \endcode
/// Destroy the mesh and the evaluator cache before the DeviceContext.

#include "osd_cull/osd/compute_evaluator.h"
#include "osd_cull/osd/device_context.h"
#include "osd_cull/osd/patch_table.h"
#include "osd_cull/osd/stencil_table.h"
#include "osd_cull/osd/vertex_buffer.h"

#include <opensubdiv/osd/mesh.h>

namespace osd_cull::osd {

/// \brief Osd::Mesh on this backend.
using VkMesh = OpenSubdiv::Osd::Mesh<VkVertexBuffer, VkStencilTable, VkComputeEvaluator,
                                     VkPatchTable, DeviceContext>;
/// \brief The evaluator cache Osd::Mesh takes (one kernel instance per buffer layout).
using VkEvaluatorCache = OpenSubdiv::Osd::EvaluatorCacheT<VkComputeEvaluator>;

}  // namespace osd_cull::osd
