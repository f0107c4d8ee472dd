// The figure helpers shared by the batch plots and the Fig. 2 composite (viz/canvas.h):
// text widths in the 5 × 7 font, text cut to fit, and round tick steps.

#include <gtest/gtest.h>

#include "viz/canvas.h"

namespace rescuesim {
namespace {

TEST(TextWidth, SixPixelsAGlyphLessTheLastGapTimesScale) {
  EXPECT_EQ(text_width("", 3), 0);
  EXPECT_EQ(text_width("a", 1), 5);
  EXPECT_EQ(text_width("abc", 2), (3 * 6 - 1) * 2);
  // the width drawn is the width reported
  Canvas c(100, 20);
  EXPECT_EQ(c.text(0, 0, "abc", {0, 0, 0}, 2), text_width("abc", 2));
}

TEST(FitText, UnchangedWhenItFitsElseCutWithDots) {
  EXPECT_EQ(fit_text("hello", 29), "hello");  // 5 glyphs: 29 px
  // 28 px: "he.." is 4 glyphs = 23 px, "hel.." 5 glyphs = 29 px: too wide
  EXPECT_EQ(fit_text("hello", 28), "he..");
  EXPECT_EQ(fit_text("hello", 46, 2), "he..");  // scale 2: "he.." 46 px
  EXPECT_EQ(fit_text("hello", 3), "..");        // nothing fits but the dots
}

TEST(NiceStep, OneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(nice_step(10, 6), 2);      // raw 1.67 → 2
  EXPECT_DOUBLE_EQ(nice_step(10, 10), 1);     // raw 1 → 1
  EXPECT_DOUBLE_EQ(nice_step(25, 8), 5);      // raw 3.1 → 5
  EXPECT_DOUBLE_EQ(nice_step(0.7, 6), 0.2);   // raw 0.117 → 0.2
  EXPECT_DOUBLE_EQ(nice_step(800, 6), 200);   // raw 133 → 200
  EXPECT_DOUBLE_EQ(nice_step(70, 10), 10);    // raw 7 → 10
}

}  // namespace
}  // namespace rescuesim
