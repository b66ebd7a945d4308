// Shared pass conventions: the reference-resolution scale.
#include <gtest/gtest.h>

#include "passes/pass_common.h"

namespace sylva::test {
namespace {

TEST(PassCommon, ReferenceScaleFollowsTheShorterSide) {
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(1024, 1024)), 1.0);
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(4096, 2048)), 2.0);
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(256, 512)), 0.25);
}

}  // namespace
}  // namespace sylva::test
