#include "osd_cull/vk/validation.h"

namespace osd_cull::vulkan {

void ValidationLog::record(ValidationMessage message) {
  std::lock_guard lock(mutex_);
  messages_.push_back(std::move(message));
}

std::vector<ValidationMessage> ValidationLog::messages() const {
  std::lock_guard lock(mutex_);
  return messages_;
}

size_t ValidationLog::count() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

void ValidationLog::clear() {
  std::lock_guard lock(mutex_);
  messages_.clear();
}

std::string ValidationLog::summary() const {
  std::lock_guard lock(mutex_);
  std::string out;
  for (const auto& m : messages_) {
    out += m.severity == ValidationMessage::Severity::Error ? "[error] " : "[warning] ";
    out += m.text;
    out += '\n';
  }
  return out;
}

}  // namespace osd_cull::vulkan
