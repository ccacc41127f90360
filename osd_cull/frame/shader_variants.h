#pragma once
/// \file shader_variants.h
/// \brief Every shader variant the library can request, listed by the modules that request
/// them: the build compiles this list to SPIR-V (tools/embed_spirv.cpp) and embeds it in the
/// library (osd_cull/vk/shader_compiler.h).
///
/// A module that requests a variant (vulkan::compileShader / compileGlsl, a ComputeProgram)
/// lists every variant it can request in its function below, defined next to the request and
/// built by the same code (the cull kernel: every combination of the registered methods
/// through the kernel's own composer). A request missing from its list fails with an error
/// naming the variant, in the tests as in a program.

#include "osd_cull/osd/shader_variants.h"
#include "osd_cull/vk/shader_compiler.h"

#include <vector>

namespace osd_cull::frame {

/// \brief The union of the lists below and of the osd layer's (osd/shader_variants.h),
/// each variant once.
std::vector<vulkan::ShaderVariant> libraryShaderVariants();

// One list per requesting module.
std::vector<vulkan::ShaderVariant> rendererShaderVariants();    // draw/renderer.cpp
std::vector<vulkan::ShaderVariant> cullPassShaderVariants();    // cull/cull_pass.cpp
std::vector<vulkan::ShaderVariant> boundsPassShaderVariants();  // cull/bounds_pass.cpp
std::vector<vulkan::ShaderVariant> hizPyramidShaderVariants();  // hiz/hiz_pyramid.cpp
std::vector<vulkan::ShaderVariant> visibilityShaderVariants();  // hiz/visibility_buffer.cpp
std::vector<vulkan::ShaderVariant> oracleShaderVariants();      // verify/visibility_oracle.cpp

}  // namespace osd_cull::frame
