// pack() never outputs a triangle of zero area (issue 17): distinct remeshed vertices that round to one point, or
// corners that round onto one line, are separated before the stream is written. The awkward meshes of the issue (a
// bowtie, CGAL's elephant, a 1 x 1 x 0.002 box) at the cheapest settings that take the same path (one bit depth,
// one step, the grid searched for a target error, the heights chosen by rate and distortion); the input checks
// that come before any remeshing (coordinates, orientation).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "prm/error.h"
#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"
#include "prm/vec3.h"
#include "awkward_meshes.h"
#include "test_meshes.h"

namespace {

using prm::Mesh;
using prm::operator*;
using prm::operator+;
using prm::pipeline::PackOptions;
using prm::test::bowtie;
using prm::test::box;

void expect_no_zero_area(const Mesh& input, double target, int bits) {
  PackOptions o;
  o.target_error = target;
  o.bits = bits;
  o.step_scale = 1;
  o.mode = prm::pipeline::PackMode::prm;  // the remesher's path (auto may keep the input for a box)
  const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
  const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status.message;
  EXPECT_EQ(prm::pipeline::count_zero_area_triangles(decoded.value), 0u);
  EXPECT_EQ(r.remesh.prm.stats.quantized_unresolved, 0u);
  EXPECT_LE(r.remesh.error.rms, target);
  std::printf("%zu vertices, %zu bytes, %zu vertices moved off collapsing positions\n", decoded.value.num_vertices(),
              r.stream.size(), r.remesh.prm.stats.quantized_moves);
}

TEST(PackDegenerate, Bowtie) { expect_no_zero_area(bowtie(), 2e-4, 12); }  // 24 zero-area triangles before

TEST(PackDegenerate, ThinBox) { expect_no_zero_area(box(1, 1, 0.002, 10), 2e-4, 12); }  // 6 before

TEST(PackDegenerate, CgalElephant) {
  const std::string path = std::string(PRM_CGAL_MESHES) + "/elephant.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing";
  expect_no_zero_area(prm::read_mesh(path), 5e-4, 11);  // 5 zero-area triangles before the separation
}

TEST(PackDegenerate, RefusedBeforeRemeshing) {
  PackOptions o;
  o.target_error = 1e-3;
  Mesh sphere = prm::test::icosphere(2);
  auto message = [&](const Mesh& m) -> std::string {
    try {
      prm::pipeline::pack(m, o);
    } catch (const prm::InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  Mesh flipped = sphere;
  std::swap(flipped.triangles[7][1], flipped.triangles[7][2]);
  EXPECT_NE(message(flipped).find("not consistently oriented"), std::string::npos) << message(flipped);
  Mesh point = sphere;
  for (prm::Vec3& p : point.positions) p = {1, 2, 3};
  EXPECT_NE(message(point).find("all the vertices coincide"), std::string::npos) << message(point);
  Mesh huge = sphere;
  for (prm::Vec3& p : huge.positions) p = p * 1e300;
  EXPECT_NE(message(huge).find("at most 1e+64"), std::string::npos) << message(huge);
  Mesh far = sphere;
  for (prm::Vec3& p : far.positions) p[0] += 1e12;
  EXPECT_NE(message(far).find("too narrow to quantize"), std::string::npos) << message(far);
}

}  // namespace
