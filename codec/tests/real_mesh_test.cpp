// Round trips on every mesh of CGAL's data set and of ../shared/meshes (§6, §10): every manifold mesh must decode
// to its own connectivity (up to the order of §6.6) and its quantized positions exactly; every other mesh must be
// refused with the error naming its defect (§6.1). Real-mesh tests fail, not skip, when the data is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include "roundtrip_util.h"

namespace prm::codec::test {
namespace {

struct Tally {
  std::vector<std::string> round_tripped, refused, unreadable;
};

Error expected_refusal(const std::string& problem) {
  if (problem.rfind("degenerate", 0) == 0) return Error::degenerate_triangle;
  if (problem.rfind("edge with three", 0) == 0) return Error::non_manifold_edge;
  if (problem.rfind("inconsistent", 0) == 0) return Error::inconsistent_orientation;
  return Error::non_manifold_vertex;
}

void run_directory(const std::string& dir, Tally& tally) {
  const auto files = list_files(dir, {".off", ".obj", ".ply"});
  ASSERT_FALSE(files.empty()) << "no meshes in " << dir << " (the data must be present)";
  for (const std::string& path : files) {
    const std::string name = std::filesystem::path(path).filename().string();
    TestMesh m;
    try {
      m = load_mesh(path);
    } catch (const std::exception& e) {
      tally.unreadable.push_back(name + " (" + e.what() + ")");
      continue;
    }
    const std::string problem = manifold_problem(m);
    if (problem.empty()) {
      EXPECT_TRUE(round_trip(m)) << name;
      tally.round_tripped.push_back(name);
    } else {
      const auto enc = encode(m.xyz.data(), m.num_vertices(), m.triangles.data(), m.num_triangles());
      ASSERT_FALSE(enc.ok()) << name << " is not manifold (" << problem << ") but was encoded";
      EXPECT_EQ(enc.status.error, expected_refusal(problem))
          << name << ": " << problem << " / " << error_name(enc.status.error) << ": " << enc.status.message;
      tally.refused.push_back(name + " (" + error_name(enc.status.error) + ")");
    }
  }
}

void print(const char* what, const std::vector<std::string>& names) {
  std::printf("%s (%zu):", what, names.size());
  for (const auto& n : names) std::printf(" %s", n.c_str());
  std::printf("\n");
}

TEST(RealMeshes, CgalDataSet) {
  Tally t;
  run_directory(PRM_CGAL_MESHES, t);
  print("round-tripped", t.round_tripped);
  print("refused (not manifold)", t.refused);
  print("not read by the test loader", t.unreadable);
  const std::set<std::string> done(t.round_tripped.begin(), t.round_tripped.end());
  for (const char* must : {"bunny00.off", "refined_elephant.off", "armadillo.off", "camel.off", "cow.off",
                           "elephant-with-holes.off", "elephant.off", "double-torus-example.off", "knot1.off"})
    EXPECT_TRUE(done.count(must)) << must << " must round-trip";
  EXPECT_GE(t.round_tripped.size(), 100u);
}

TEST(RealMeshes, SharedMeshes) {
  Tally t;
  run_directory(PRM_SHARED_MESHES, t);
  print("round-tripped", t.round_tripped);
  print("refused (not manifold)", t.refused);
  EXPECT_TRUE(t.unreadable.empty());
  EXPECT_EQ(t.round_tripped.size(), 9u);
  ASSERT_EQ(t.refused.size(), 1u);
  EXPECT_EQ(t.refused[0], "rabbit_1k_decimated.off (non_manifold_vertex)");
}

}  // namespace
}  // namespace prm::codec::test
