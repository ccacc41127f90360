#include "osd_cull/scene/procedural_displacement.h"

#include "osd_cull/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

namespace osd_cull::scene {
namespace {

// A 32-bit integer hash (lowbias32) of a lattice point: the lattice value in [0, 1).
double latticeValue(uint32_t x, uint32_t y, uint32_t octave, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ octave * 0xcb1ab31fu ^ seed * 0x9e3779b9u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return (h >> 8) * (1.0 / 16777216.0);
}

double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

}  // namespace

std::vector<float> proceduralDisplacementTexels(uint32_t size, uint32_t octaves, uint32_t seed) {
  if (size < 8 || size > 4096 || !std::has_single_bit(size))
    throw Error("procedural displacement: size " + std::to_string(size) +
                " must be a power of two in [8, 4096]");
  if (octaves < 1 || (4u << (octaves - 1)) > size)
    throw Error("procedural displacement: " + std::to_string(octaves) +
                " octave(s) need 1..log2(size) - 1 (finest lattice at most one cell per texel)");
  std::vector<double> sum(static_cast<size_t>(size) * size, 0.0);
  for (uint32_t k = 0; k < octaves; ++k) {
    const uint32_t cells = 4u << k;
    const double amplitude = std::ldexp(1.0, -static_cast<int>(k));
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        // Texel centres, in lattice cells; the lattice wraps so the noise has period 1.
        const double fx = (x + 0.5) * cells / size, fy = (y + 0.5) * cells / size;
        const auto cx = static_cast<uint32_t>(fx), cy = static_cast<uint32_t>(fy);
        const double ax = smooth(fx - cx), ay = smooth(fy - cy);
        const uint32_t nx = (cx + 1) % cells, ny = (cy + 1) % cells;
        const double v =
            (1 - ay) *
                ((1 - ax) * latticeValue(cx, cy, k, seed) + ax * latticeValue(nx, cy, k, seed)) +
            ay * ((1 - ax) * latticeValue(cx, ny, k, seed) + ax * latticeValue(nx, ny, k, seed));
        sum[static_cast<size_t>(y) * size + x] += amplitude * v;
      }
  }
  const auto [lo, hi] = std::minmax_element(sum.begin(), sum.end());
  const double a = *lo, range = std::max(*hi - *lo, 1e-12);
  std::vector<float> texels(sum.size());
  for (size_t i = 0; i < sum.size(); ++i)
    texels[i] = static_cast<float>(std::clamp((sum[i] - a) / range, 0.0, 1.0));
  return texels;
}

}  // namespace osd_cull::scene
