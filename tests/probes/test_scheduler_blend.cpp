// Sample-aware blending (accumulation.h): weights from the samples a probe has received, the
// hysteresis cap, age decay, and the per-frame equivalent hysteresis the scheduler passes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "probes/accumulation.h"
#include "probes/probe_volume.h"
#include "sh/sh_rgb.h"

using namespace ddish::probes;

TEST(SampleBlend, FullSamplesEveryFrameIsThePerUpdateRule) {
  // n = S each frame, age 1: w_k = S / ((k-1) S + S) = 1/k until the history reaches
  // N = S alpha / (1 - alpha), then 1 - alpha: exactly max(1/k, 1 - alpha).
  for (float alpha : {0.0f, 0.5f, 0.9f, 0.95f}) {
    const std::uint32_t S = 256;
    for (std::uint32_t k = 1; k <= 100; ++k) {
      BlendHistory h{k - 1, std::uint64_t(k - 1) * S, 1};
      EXPECT_NEAR(sample_blend_weight(h, S, alpha, S), blend_weight(k, alpha), 1e-6f)
          << alpha << " " << k;
      EXPECT_EQ(blend_weight(BlendRule::per_update, h, 17, alpha, S), blend_weight(k, alpha));
    }
  }
}

TEST(SampleBlend, ExactSampleWeightedMeanBeforeTheCap) {
  // Updates of 10, 30 and 60 samples with estimates 1, 2, 4: weights 1, 30/40, 60/100, and
  // the average is the mean over all 100 samples, (10 + 60 + 240) / 100 = 3.1.
  const float alpha = 0.99f;  // cap 256 * 99 = 25344 samples: far away
  const std::vector<std::uint64_t> n{10, 30, 60};
  const std::vector<float> e{1.0f, 2.0f, 4.0f};
  const std::vector<float> w_expected{1.0f, 0.75f, 0.6f};
  BlendHistory h;
  float avg = 0.0f;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const float w = sample_blend_weight(h, n[i], alpha, 256);
    EXPECT_FLOAT_EQ(w, w_expected[i]);
    avg += w * (e[i] - avg);
    h.updates += 1;
    h.samples += n[i];
  }
  EXPECT_FLOAT_EQ(avg, 3.1f);
}

TEST(SampleBlend, FewerSamplesWeighLessOnceConverged) {
  // alpha 0.9, S 100: N = 900. A converged probe given 50 samples: 50 / 950; given 100: 0.1.
  BlendHistory converged{50, 5000, 1};
  EXPECT_NEAR(sample_blend_weight(converged, 50, 0.9f, 100), 50.0f / 950.0f, 1e-7f);
  EXPECT_NEAR(sample_blend_weight(converged, 100, 0.9f, 100), 0.1f, 1e-7f);
  EXPECT_NEAR(sample_blend_weight(converged, 400, 0.9f, 100), 400.0f / 1300.0f, 1e-7f);
  EXPECT_FLOAT_EQ(sample_blend_weight(BlendHistory{}, 5, 0.9f, 100), 1.0f);  // empty history
}

TEST(SampleBlend, StaleHistoryDecaysByAlphaPerMissedFrame) {
  // Missed 10 frames (age 11): cap 900 * 0.9^10 = 313.8; w = 100 / 413.8.
  const double cap = 900.0 * std::pow(0.9, 10.0);
  BlendHistory stale{50, 5000, 11};
  EXPECT_NEAR(sample_blend_weight(stale, 100, 0.9f, 100), float(100.0 / (cap + 100.0)), 1e-6f);
  // A young probe whose history is below the decayed cap keeps its exact mean.
  BlendHistory young{1, 100, 11};
  EXPECT_NEAR(sample_blend_weight(young, 100, 0.9f, 100), 0.5f, 1e-7f);
  // Age 0 (not aged by an update yet) counts as updated every frame.
  EXPECT_NEAR(sample_blend_weight(BlendHistory{50, 5000, 0}, 100, 0.9f, 100), 0.1f, 1e-7f);
  // alpha 0: no history at all, whatever the age.
  EXPECT_FLOAT_EQ(sample_blend_weight(BlendHistory{3, 300, 1}, 100, 0.0f, 100), 1.0f);
}

TEST(SampleBlend, EquivalentHysteresisGivesTheSteadyStateWeight) {
  const float alpha = 0.95f;
  const std::uint32_t S = 256;
  EXPECT_EQ(sample_equivalent_hysteresis(alpha, S, S), alpha);
  for (std::uint32_t n : {16u, 64u, 128u, 512u}) {
    const float a = sample_equivalent_hysteresis(alpha, S, n);
    check_hysteresis(a);
    BlendHistory converged{1000, 1000ull * S, 1};
    // Per-update rule with a' on a converged probe == per-sample rule with n samples.
    EXPECT_NEAR(blend_weight(1000, a), sample_blend_weight(converged, n, alpha, S), 1e-6f) << n;
  }
  EXPECT_LT(sample_equivalent_hysteresis(0.999999f, 1, 1000000), 1.0f);
}

TEST(SampleBlend, RuleNames) {
  EXPECT_EQ(parse_blend_rule("per-update"), BlendRule::per_update);
  EXPECT_EQ(parse_blend_rule("per-sample"), BlendRule::per_sample);
  EXPECT_STREQ(blend_rule_name(BlendRule::per_sample), "per-sample");
  EXPECT_THROW(parse_blend_rule("samples"), std::invalid_argument);
}

// The volume applies the rule it is given: a half-sample update of a probe with S samples of
// history gets n / (h + n) = 128 / (256 + 128) = 1/3 under per_sample and 1/2 under per_update.
TEST(VolumeBlend, PerSampleRuleWeighsSamples) {
  using namespace ddish;
  for (auto rule : {probes::BlendRule::per_sample, probes::BlendRule::per_update}) {
    probes::ProbeVolume volume(probes::ProbeGrid(), 2);
    sh::ShRgb one(2), four(2);
    one.c[0] = glm::vec3(1.0f);
    four.c[0] = glm::vec3(4.0f);
    volume.begin_update();
    volume.accumulate(0, one, 256, 0.95f, rule, 256);
    volume.begin_update();
    volume.accumulate(0, four, 128, 0.95f, rule, 256);
    const float expected_w = rule == probes::BlendRule::per_sample ? 1.0f / 3.0f : 0.5f;
    EXPECT_NEAR(volume.coefficients(0)[0].x, 1.0f + expected_w * 3.0f, 1e-6f);
  }
}
