// The timing discipline's statistics against values worked by hand: the median and its interval
// (inside the data, deterministic for a seed), ratios of paired medians, verdicts that never rank
// what the interval cannot tell apart, the coefficient of variation, and the noise thresholds.
#include "reports/timing.h"

#include <gtest/gtest.h>

namespace meshreuse {
namespace {

TEST(Timing, SpreadOfRounds) {
  const std::vector<double> v = {3, 1, 2, 10, 4};
  const Spread s = SpreadOf(v, 7);
  EXPECT_EQ(s.median, 3);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.max, 10);
  EXPECT_LE(s.lo, 3);  // a bootstrap interval of a median lies within the data
  EXPECT_GE(s.hi, 3);
  EXPECT_GE(s.lo, 1);
  EXPECT_LE(s.hi, 10);
  const Spread again = SpreadOf(v, 7);
  EXPECT_EQ(s.lo, again.lo);  // seeded: the same interval every time
  EXPECT_EQ(s.hi, again.hi);
  const Spread one = SpreadOf({5, 5, 5}, 1);  // no variation: an exact interval
  EXPECT_EQ(one.lo, 5);
  EXPECT_EQ(one.hi, 5);
}

TEST(Timing, RatiosAndVerdicts) {
  const std::vector<double> a = {10, 11, 10.5, 10.2, 10.8}, b = {5, 5.5, 5.2, 5.1, 5.4};
  const Spread r = RatioOfMedians(a, b, 3);  // twice as fast, every round
  EXPECT_NEAR(r.median, 10.5 / 5.2, 1e-12);
  EXPECT_GT(r.lo, 1.8);
  EXPECT_EQ(SpeedupVerdict(r), Verdict::kFaster);
  EXPECT_EQ(SpeedupVerdict(RatioOfMedians(b, a, 3)), Verdict::kSlower);
  // The same times shuffled: the interval holds 1, never ranked.
  const std::vector<double> c = {10.8, 10, 10.2, 11, 10.5};
  EXPECT_EQ(SpeedupVerdict(RatioOfMedians(a, c, 3)), Verdict::kNotDistinguishable);
  EXPECT_EQ(SpeedupVerdict(Spread{1, 1, 1, 1, 1}), Verdict::kReference);
  EXPECT_EQ(SpeedupVerdict(Spread()), Verdict::kNotDistinguishable);  // unknown
  EXPECT_EQ(GainVerdict(Spread{0.1, 0.05, 0.2, 0.02, 0.15}), Verdict::kFaster);
  EXPECT_EQ(GainVerdict(Spread{0.01, -0.05, 0.2, -0.02, 0.05}), Verdict::kNotDistinguishable);
  EXPECT_STREQ(VerdictName(Verdict::kNotDistinguishable), "not distinguishable");
}

TEST(Timing, CoefficientOfVariationAndNoise) {
  EXPECT_NEAR(CoefficientOfVariation({2, 4, 4, 4, 5, 5, 7, 9}), 2.138089935 / 5, 1e-9);
  Noise quiet;
  quiet.cores = 2, quiet.load_before = 0.3, quiet.load_after = 1.1;
  quiet.cpu_per_wall = 0.98, quiet.cv = 0.01;
  EXPECT_TRUE(quiet.Reasons().empty());
  Noise busy = quiet;
  busy.load_after = 8.5;
  busy.cpu_per_wall = 0.6;
  busy.cv = 0.2;
  const std::vector<std::string> why = busy.Reasons();
  ASSERT_EQ(why.size(), 3u);
  EXPECT_NE(why[0].find("above the 2 cores"), std::string::npos) << why[0];
  EXPECT_NE(why[1].find("60%"), std::string::npos) << why[1];
  EXPECT_NE(why[2].find("20.0%"), std::string::npos) << why[2];
  EXPECT_TRUE(busy.ToJson()["busy"].get<bool>());
}

}  // namespace
}  // namespace meshreuse
