#pragma once
/// \file error.h
/// \brief The exception osd_cull throws at its API boundary.

#include <stdexcept>
#include <string>

namespace osd_cull {

/// \brief Raised for bad input or a failed device call. The message names the context
/// a user needs: file and line, which option, which Vulkan call and its VkResult.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace osd_cull
