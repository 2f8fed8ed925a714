// The seam collapses' memo of triangle answers (triangle_answer_memo.h) against a std::map.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <random>

#include "../src/triangle_answer_memo.h"

namespace prm::remesh {
namespace {

TEST(SeamTriangleAnswerMemo, AgreesWithAMapThroughGrowthAndClear) {
  TriangleAnswerMemo memo;
  std::map<std::array<int32_t, 3>, bool> reference;
  std::mt19937 rng(7);
  // Small index ranges, so that triples repeat and differ in one index only; 40,000 triples grow the table past
  // several doublings (it starts at 4,096 slots).
  std::uniform_int_distribution<int32_t> index(0, 60);
  for (int i = 0; i < 60000; ++i) {
    const int32_t y = index(rng), a = index(rng), b = index(rng);
    const auto it = reference.find({y, a, b});
    const int known = memo.find(y, a, b);
    if (it == reference.end()) {
      ASSERT_EQ(known, -1) << y << " " << a << " " << b;
      const bool ok = (rng() & 1) != 0;
      memo.add(y, a, b, ok);
      reference[{y, a, b}] = ok;
    } else {
      ASSERT_EQ(known, it->second ? 1 : 0) << y << " " << a << " " << b;
    }
  }
  ASSERT_GT(reference.size(), 40000u);
  // The order of a triple matters: (y, a, b) and (y, b, a) are different triangles (opposite orientation).
  memo.clear();
  memo.add(1, 2, 3, true);
  EXPECT_EQ(memo.find(1, 2, 3), 1);
  EXPECT_EQ(memo.find(1, 3, 2), -1);
  EXPECT_EQ(memo.find(2, 3, 1), -1);
  memo.clear();
  EXPECT_EQ(memo.find(1, 2, 3), -1);
}

}  // namespace
}  // namespace prm::remesh
