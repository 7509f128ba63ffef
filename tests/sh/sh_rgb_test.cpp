#include <cmath>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "sh/sh_rgb.h"

namespace ddish::sh {
namespace {

TEST(ShRgb, ArithmeticAndOrders) {
  ShRgb a(1), b(2);
  EXPECT_EQ(a.count(), 4);
  EXPECT_EQ(b.count(), 9);
  a[0] = glm::vec3(1.0f, 2.0f, 3.0f);
  a[3] = glm::vec3(0.5f);
  b[0] = glm::vec3(1.0f);
  b[8] = glm::vec3(-2.0f);
  const ShRgb s = a + b;
  EXPECT_EQ(s.order, 2);
  EXPECT_EQ(s[0], glm::vec3(2.0f, 3.0f, 4.0f));
  EXPECT_EQ(s[8], glm::vec3(-2.0f));
  const ShRgb d = 2.0f * (s - b);
  EXPECT_EQ(d[0], glm::vec3(2.0f, 4.0f, 6.0f));
  EXPECT_EQ(d[8], glm::vec3(0.0f));
  ShRgb c = s;
  c *= glm::vec3(1.0f, 0.0f, 2.0f);
  EXPECT_EQ(c[0], glm::vec3(2.0f, 0.0f, 8.0f));
  // Lowering the order zeroes the dropped bands, so raising it again gives zeros there.
  c.set_order(1);
  c.set_order(2);
  EXPECT_EQ(c[8], glm::vec3(0.0f));
  EXPECT_EQ(c.coeffs().size(), 9u);
  EXPECT_EQ(ShRgb(7).order, 4);
  EXPECT_EQ(ShRgb(-1).order, 0);
}

TEST(ShRgb, LerpAndChecks) {
  ShRgb a(2), b(2);
  a[4] = glm::vec3(1.0f);
  b[4] = glm::vec3(3.0f);
  EXPECT_EQ(lerp(a, b, 0.25f)[4], glm::vec3(1.5f));
  EXPECT_EQ(max_abs(b), 3.0f);
  EXPECT_TRUE(all_finite(b));
  b[2].y = std::nanf("");
  EXPECT_FALSE(all_finite(b));
  // Values past the order are not part of the function.
  ShRgb c(1);
  c[9] = glm::vec3(INFINITY);
  EXPECT_TRUE(all_finite(c));
}

TEST(ShRgb, EvalOfConstant) {
  ShRgb c(3);
  c[0] = glm::vec3(2.0f * 0.28209479f);
  const glm::vec3 v = eval(c, glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f)));
  EXPECT_NEAR(v.x, 2.0f * 0.28209479f * 0.28209479f, 1e-6f);
}

}  // namespace
}  // namespace ddish::sh
