// The 8-bit sRGB code (platform/colour.h): the table's answer is the transfer function's, rounded,
// around every step where the code goes up and across the whole range. (Every float in
// [0, 1.5] was compared once when the table was written: none differed.)
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "platform/colour.h"

namespace rockbake {
namespace {

std::uint8_t direct(float linear) {
  return std::uint8_t(std::lround(linearToSrgb(linear) * 255.0f));
}

TEST(SrgbByte, IsTheTransferFunctionRoundedNearEveryStep) {
  int steps = 0;
  for (int code = 1; code <= 255; ++code) {
    // The step up to `code`: from the linear value its sRGB value's midpoint decodes to.
    const float middle = srgbToLinear((code - 0.5f) / 255.0f);
    const std::uint32_t at = std::bit_cast<std::uint32_t>(middle);
    for (std::uint32_t u = at - 512; u <= at + 512; ++u) {
      const float x = std::bit_cast<float>(u);
      ASSERT_EQ(linearToSrgbByte(x), direct(x)) << "at " << x << " (code " << code << ")";
    }
    steps += direct(std::bit_cast<float>(at - 512)) < direct(std::bit_cast<float>(at + 512));
  }
  EXPECT_EQ(steps, 255);  // each window held its step
}

TEST(SrgbByte, IsTheTransferFunctionRoundedAcrossTheRange) {
  for (int i = 0; i <= 1000000; ++i) {
    const float x = float(i) / 800000.0f;  // 0 … 1.25
    ASSERT_EQ(linearToSrgbByte(x), direct(x)) << "at " << x;
  }
}

TEST(SrgbByte, ClampsOutOfRangeAndNaN) {
  EXPECT_EQ(linearToSrgbByte(-1.0f), 0);
  EXPECT_EQ(linearToSrgbByte(0.0f), 0);
  EXPECT_EQ(linearToSrgbByte(1.0f), 255);
  EXPECT_EQ(linearToSrgbByte(7.0f), 255);
  EXPECT_EQ(linearToSrgbByte(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(linearToSrgbByte(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(linearToSrgbByte(0.18f), 118);  // middle grey
}

}  // namespace
}  // namespace rockbake
