// A test suite sharing one single-process renderer (one device context): tests replace its mesh.
// The suite fails when the validation layer reported anything.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "shellmarch/insitu.h"

namespace sm::insitu::test {

class RendererSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { vis_ = std::make_unique<shellmarch::insitu::Renderer>(); }
  static void TearDownTestSuite() {
    // Absent when SetUpTestSuite threw (no usable device): its failure is already reported.
    if (vis_) {
      EXPECT_EQ(vis_->stats().validationErrors, 0u);
    }
    vis_.reset();
  }
  static inline std::unique_ptr<shellmarch::insitu::Renderer> vis_;
};

}  // namespace sm::insitu::test
