#pragma once
/// \file bench_support.h
/// \brief Small helpers shared by the benchmarks.

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace osd_cull::bench {

/// \brief The median (mean of the two middle values for an even count); 0 when empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// \brief A comma-separated list of unsigned numbers ("4,8,16").
/// \throws std::invalid_argument or std::out_of_range for an item that is not a number.
inline std::vector<uint32_t> numberList(const std::string& text) {
  std::vector<uint32_t> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(static_cast<uint32_t>(std::stoul(item)));
  return out;
}

}  // namespace osd_cull::bench
