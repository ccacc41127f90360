#include "support/vk_test_context.h"

namespace osd_cull::test {

vk::ContextOptions validatedContextOptions(std::shared_ptr<vk::ValidationLog> log) {
  vk::ContextOptions options;
  options.validation = true;
  options.validationLog = std::move(log);
  return options;
}

void VkTest::SetUp() {
  log_ = std::make_shared<vk::ValidationLog>();
  context_ = std::make_unique<vk::Context>(validatedContextOptions(log_));
}

void VkTest::TearDown() {
  context_.reset();
  EXPECT_EQ(log_->count(), 0u) << "Vulkan validation reported:\n" << log_->summary();
}

}  // namespace osd_cull::test
