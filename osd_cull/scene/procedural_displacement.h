#pragma once
/// \file procedural_displacement.h
/// \brief A displacement map generated in code (noise at several scales), so tests and the
/// demo need no image file. It is an ordinary texture sampled through the mesh's texture
/// coordinates (face-varying UVs), so the draw, the bounds and the oracle treat it exactly
/// like a map read from a file.

#include <cstdint>
#include <vector>

namespace osd_cull::scene {

/// \brief `size` x `size` texels in [0, 1] (size a power of two, 8..4096): the sum of
/// `octaves` layers of periodic value noise (smoothstep-interpolated random lattice
/// values), layer k with 4 * 2^k cells per side and amplitude 2^-k, normalised to [0, 1].
/// The noise repeats with period 1 in s and t, so `repeat` addressing is seamless.
/// Deterministic for a given seed.
/// \throws osd_cull::Error for a size or octave count out of range.
std::vector<float> proceduralDisplacementTexels(uint32_t size = 256, uint32_t octaves = 4,
                                                uint32_t seed = 1);

}  // namespace osd_cull::scene
