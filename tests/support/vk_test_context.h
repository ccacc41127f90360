#pragma once
/// \file vk_test_context.h
/// \brief Every Vulkan test runs with validation on and fails on any validation message.

#include "osd_cull/vk/context.h"

#include <gtest/gtest.h>

#include <memory>

namespace osd_cull::test {

/// \brief Context options of tests: validation with synchronization validation, device
/// from $OSD_CULL_DEVICE (lavapipe by default).
vulkan::ContextOptions validatedContextOptions(std::shared_ptr<vulkan::ValidationLog> log);

/// \brief Fixture: SetUp creates a validated Context; TearDown destroys it and then fails
/// the test if the validation layer reported anything (during the test or at teardown).
///
/// Vulkan objects must be gone before TearDown: keep them local to the test body, or
/// reset them in the derived fixture's TearDown before calling VkTest::TearDown().
class VkTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  vulkan::Context& context() { return *context_; }
  vulkan::ValidationLog& validationLog() { return *log_; }

 private:
  std::shared_ptr<vulkan::ValidationLog> log_;
  std::unique_ptr<vulkan::Context> context_;
};

}  // namespace osd_cull::test
