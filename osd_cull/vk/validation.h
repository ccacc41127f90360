#pragma once
/// \file validation.h
/// \brief Messages of the Khronos validation layer, recorded for tests and tools.

#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

namespace osd_cull::vulkan {

/// \brief One message the validation layer reported (warning or error).
struct ValidationMessage {
  enum class Severity { Warning, Error };
  Severity severity = Severity::Error;
  std::string id;    ///< VUID or message id name, e.g. "SYNC-HAZARD-WRITE-AFTER-READ"
  std::string text;  ///< the layer's full message
};

/// \brief Thread-safe list of validation messages. A Context with validation on writes
/// into one; a test checks it is empty when the test ends (tests/support/vk_test_context.h).
class ValidationLog {
 public:
  /// \brief Appends a message (called from the debug messenger, any thread).
  void record(ValidationMessage message);
  /// \brief A copy of all messages so far.
  std::vector<ValidationMessage> messages() const;
  /// \brief Number of messages so far.
  size_t count() const;
  /// \brief Forgets all messages.
  void clear();
  /// \brief All messages as text, one per line ("" when none).
  std::string summary() const;

 private:
  mutable std::mutex mutex_;
  std::vector<ValidationMessage> messages_;
};

}  // namespace osd_cull::vulkan
