// The embedded-SPIR-V index of the generator itself (tools/embed_spirv.cpp), which compiles
// the variants it is to embed: none.
#include "osd_cull/vk/shader_compiler.h"

namespace osd_cull::vulkan {

std::span<const EmbeddedSpirv> embeddedSpirv() { return {}; }
std::span<const uint32_t> embeddedSpirvWords() { return {}; }
uint64_t embeddedSpirvWordsHash() { return fnv1a64(""); }

}  // namespace osd_cull::vulkan
