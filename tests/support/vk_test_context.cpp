#include "support/vk_test_context.h"

namespace osd_cull::test {

vulkan::ContextOptions validatedContextOptions(std::shared_ptr<vulkan::ValidationLog> log) {
  vulkan::ContextOptions options;
  options.validation = true;
  options.validationLog = std::move(log);
  return options;
}

void VkTest::SetUp() {
  log_ = std::make_shared<vulkan::ValidationLog>();
  context_ = std::make_unique<vulkan::Context>(validatedContextOptions(log_));
}

void VkTest::TearDown() {
  context_.reset();
  EXPECT_EQ(log_->count(), 0u) << "Vulkan validation reported:\n" << log_->summary();
}

}  // namespace osd_cull::test
