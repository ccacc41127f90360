// Lets one header declare structs for C++ and GLSL: in C++ the GLSL type names are
// aliases of GLM types in namespace osd_cull::shader.
#ifndef OSD_CULL_SHARED_GLSL_COMPAT_H
#define OSD_CULL_SHARED_GLSL_COMPAT_H
#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
namespace osd_cull::shader {
using uint = uint32_t;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
}  // namespace osd_cull::shader
#define OSD_CULL_SHARED_BEGIN namespace osd_cull::shader {
#define OSD_CULL_SHARED_END }
#define OSD_CULL_CONST inline constexpr
#else
#define OSD_CULL_SHARED_BEGIN
#define OSD_CULL_SHARED_END
#define OSD_CULL_CONST const
#endif
#endif
