// §6.5.2 Seam: Spirale Reversi with the shortcut (SpiraleReversi::Record::odd_near, init with seam_context) and
// without it (every Seam walked) must give the same Seam before every step, the same step results and the same final
// tables: on the closed meshes of real connectivity plans (valid streams) and on random step sequences (the states of
// invalid streams: closed vertices gaining triangles, handles to any edge, components closed early).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "clers.h"
#include "spirale_reversi.h"
#include "test_meshes.h"

namespace prm::codec {
namespace {
using namespace prm::codec::test;

struct Pair {
  SpiraleReversi with, without;
  uint32_t seams[2] = {0, 0};  // Seam values seen, 0 and 1: the test sees both
  void init(uint32_t nt, uint32_t nv) {
    with.init(nt, nv, true);
    without.init(nt, nv, false);
  }
  void compare_seam() {
    const uint32_t s = with.gate_start_seam();
    ASSERT_EQ(s, without.gate_start_seam());
    ASSERT_LT(s, 2u);
    ++seams[s];
  }
};

// The plan's symbols replayed as the encoder does (clers_encode.cpp), comparing the two before every step.
void replay(const TestMesh& mesh, Pair& p) {
  ConnectivityPlan plan;
  ASSERT_TRUE(plan_connectivity(mesh.triangles.data(), mesh.triangles.size() / 3, mesh.num_vertices(), plan).ok());
  const uint32_t nt = plan.mesh.num_triangles();
  p.init(nt, plan.mesh.num_vertices);
  std::vector<uint8_t> is_first(nt, 0);
  std::vector<uint32_t> comp_end;
  uint32_t s = 0;
  for (uint32_t size : plan.component_sizes) {
    is_first[s] = 1;
    s += size;
    comp_end.push_back(s);
  }
  size_t comp = comp_end.size(), h = plan.handles.size();
  for (uint32_t i = nt; i-- > 0;) {
    if (p.with.stack_depth() > 0) p.compare_seam();
    if (is_first[i]) {
      ASSERT_TRUE(p.with.close_component(i));
      ASSERT_TRUE(p.without.close_component(i));
      --comp;
    } else if (h > 0 && plan.handles[h - 1].triangle == i) {
      --h;
      ASSERT_TRUE(p.with.apply_handle(i, plan.handles[h], comp_end[comp - 1]));
      ASSERT_TRUE(p.without.apply_handle(i, plan.handles[h], comp_end[comp - 1]));
    } else {
      ASSERT_TRUE(p.with.apply(i, plan.symbols[i]));
      ASSERT_TRUE(p.without.apply(i, plan.symbols[i]));
    }
  }
  std::vector<uint32_t> a, b;
  ASSERT_TRUE(p.with.finish(a));
  ASSERT_TRUE(p.without.finish(b));
  EXPECT_EQ(a, b);
  EXPECT_EQ(p.with.opposites(), p.without.opposites());
}

TEST(SeamShortcut, SameSeamOnRealPlans) {
  Pair p;
  for (const TestMesh& m : {icosphere(3), torus(12, 9), plate_with_holes(2, 2), sphere_with_holes(3, 3),
                            hex_patch(6, true), concat({icosphere(2), torus(6, 5)})}) {
    replay(m, p);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(p.seams[0], 0u);
  EXPECT_GT(p.seams[1], 0u);
}

TEST(SeamShortcut, SameSeamOnRandomSteps) {
  std::mt19937 rng(2026);
  Pair p;
  uint32_t finished = 0;
  for (int run = 0; run < 20000; ++run) {
    const uint32_t nt = 2 + 2 * (rng() % (run % 7 == 0 ? 300 : 20));
    p.init(nt, nt / 2 + 2 + rng() % 3);
    bool ok = true;
    for (uint32_t i = nt; ok && i-- > 0;) {
      const uint32_t r = rng() % 100;
      if (p.with.stack_depth() > 0) p.compare_seam();
      if (::testing::Test::HasFatalFailure()) return;
      if (i == 0 || r < 1) {
        ok = p.with.close_component(i);
        ASSERT_EQ(ok, p.without.close_component(i));
      } else if (r < 6 && i + 1 < nt) {
        const HandleEvent e{i, i + 1 + static_cast<uint32_t>(rng() % (nt - i - 1)), static_cast<uint8_t>(rng() % 3)};
        ok = p.with.apply_handle(i, e, nt);
        ASSERT_EQ(ok, p.without.apply_handle(i, e, nt));
      } else {
        const uint32_t q = rng() % 100;
        const uint8_t sym = p.with.stack_depth() == 0 ? kE : q < 45 ? kC : q < 65 ? kR : q < 75 ? kL : q < 88 ? kS : kE;
        ok = p.with.apply(i, sym);
        ASSERT_EQ(ok, p.without.apply(i, sym));
      }
      ASSERT_EQ(p.with.error(), p.without.error());
    }
    if (!ok) continue;
    std::vector<uint32_t> a, b;
    const bool fa = p.with.finish(a);
    ASSERT_EQ(fa, p.without.finish(b));
    ASSERT_EQ(p.with.error(), p.without.error());
    if (fa) {
      ++finished;
      ASSERT_EQ(a, b);
    }
  }
  EXPECT_GT(p.seams[0], 0u);
  EXPECT_GT(p.seams[1], 0u);
  EXPECT_GT(finished, 0u);
}

}  // namespace
}  // namespace prm::codec
