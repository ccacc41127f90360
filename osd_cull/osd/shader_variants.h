#pragma once
/// \file shader_variants.h
/// \brief The shader variants the osd layer can request (the Osd compute evaluator), for
/// the library's list (frame/shader_variants.h) that the build compiles to SPIR-V. Kept in
/// this layer so that the evaluator does not reach up into frame/.

#include "osd_cull/vk/shader_compiler.h"

#include <vector>

namespace osd_cull::osd {

std::vector<vulkan::ShaderVariant> evaluatorShaderVariants();  // osd/compute_evaluator.cpp

}  // namespace osd_cull::osd
