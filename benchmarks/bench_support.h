#pragma once
/// \file bench_support.h
/// \brief Small helpers shared by the benchmarks.

#include <algorithm>
#include <vector>

namespace osd_cull::bench {

/// \brief The median (mean of the two middle values for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace osd_cull::bench
