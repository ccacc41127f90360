#pragma once
/// \file hash.h
/// \brief 64-bit FNV-1a, the one hash of cache keys and stamps (SPIR-V cache, calibration
/// cache). Not for security. The lowest layer: every part of the library may include it.

#include <cstdint>
#include <string_view>

namespace osd_cull {

/// \brief 64-bit FNV-1a hash of `bytes`, continuing from `seed` (chain calls to hash
/// several pieces).
constexpr uint64_t fnv1a64(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull) {
  uint64_t h = seed;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace osd_cull
