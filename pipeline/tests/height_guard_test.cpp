// The heights' guard of --local-refinement (pipeline/src/height_guard.h, h22max6/h22max7): which lambdas it tries,
// in which order, what it takes, and that it stops (at most kHeightGuardTries lambdas, then the rounded heights).
// The evaluator stands in for "encode with lambda j, measure at full density, meets the RMS target and 8x".
#include <gtest/gtest.h>

#include <vector>

#include "height_guard.h"

namespace prm::pipeline {
namespace {

// The RMS-chosen lambda (index 9) breaks 8x; lambdas 6 and below meet both: the largest of them is taken, after
// trying 8 and 7 (largest first), and nothing below it is tried.
TEST(PackHeightGuard, TakesTheLargestSmallerLambdaThatMeetsBoth) {
  std::vector<int> tried;
  int kept = 99;  // the stream the caller holds: the RMS-chosen one until a try meets
  const int j = height_guard_choice(9, [&](int x) {
    tried.push_back(x);
    if (x > 6) return false;
    kept = x;
    return true;
  });
  EXPECT_EQ(j, 6);
  EXPECT_EQ(kept, 6);
  EXPECT_EQ(tried, (std::vector<int>{8, 7, 6}));
}

// No lambda meets 8x, the rounded heights neither: kHeightGuardNone, the caller's stream left as it was, and at most
// kHeightGuardTries lambdas tried before the rounded heights (h22max6 tried all 15 below the 16th).
TEST(PackHeightGuard, NoneMeetsLeavesTheStreamAndStops) {
  std::vector<int> tried;
  int kept = 99;
  const int j = height_guard_choice(15, [&](int x) {
    tried.push_back(x);
    return false;
  });
  EXPECT_EQ(j, kHeightGuardNone);
  EXPECT_EQ(kept, 99);
  std::vector<int> expected;
  for (int x = 14; x > 14 - kHeightGuardTries; --x) expected.push_back(x);
  expected.push_back(-1);
  EXPECT_EQ(tried, expected);
}

// Only the rounded heights meet: reached after the capped tries; with the smallest lambda chosen (index 0) they are the
// only try.
TEST(PackHeightGuard, RoundedHeightsAsTheLastTry) {
  for (const int k : {12, 0}) {
    std::vector<int> tried;
    const int j = height_guard_choice(k, [&](int x) {
      tried.push_back(x);
      return x == -1;
    });
    EXPECT_EQ(j, -1);
    EXPECT_EQ(tried.back(), -1);
    EXPECT_EQ(tried.size(), k == 0 ? 1u : static_cast<size_t>(kHeightGuardTries) + 1);
  }
}

}  // namespace
}  // namespace prm::pipeline
