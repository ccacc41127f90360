#pragma once
/// \file shader_sources.h
/// \brief The GLSL sources of shaders/, embedded in the library at build time.

#include <span>
#include <string_view>

namespace osd_cull::vulkan::glsl {

/// \brief One embedded file: its path relative to shaders/ and its text.
struct EmbeddedShader {
  std::string_view path;
  std::string_view text;
};

/// \brief All files embedded from shaders/ (GLSL and shared headers).
std::span<const EmbeddedShader> embeddedShaders();

}  // namespace osd_cull::vulkan::glsl
