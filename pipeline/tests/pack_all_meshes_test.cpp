// Every mesh the remesher makes from ../shared/meshes and CGAL's dense meshes, at two grid sizes, through the PRM
// codec: decode(encode(m)) is exactly the quantized PRM (issue 6), and no decoded triangle has zero area (issue 17).
// Heavy: about two minutes in Release.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "prm/mesh_io.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"

namespace {

TEST(PackAllMeshes, ExactRoundTripAtTwoGridSizes) {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(PRM_SHARED_MESHES)) {
    const std::string ext = e.path().extension().string();
    if (ext == ".ply" || ext == ".off" || ext == ".obj") files.push_back(e.path().string());
  }
  for (const char* f : {"bunny00.off", "refined_elephant.off", "armadillo.off", "camel.off", "cow.off", "homer.off",
                        "elephant.off", "man.off"})
    files.push_back(std::string(PRM_CGAL_MESHES) + "/" + f);
  std::sort(files.begin(), files.end());
  for (const std::string& path : files) {
    const prm::Mesh input = prm::read_mesh(path);
    for (double fraction : {0.008, 0.015}) {
      SCOPED_TRACE(path + " at grid fraction " + std::to_string(fraction));
      prm::pipeline::PackOptions o;
      o.grid_fraction = fraction;
      const prm::pipeline::PackResult r = prm::pipeline::pack(input, o);
      EXPECT_GT(r.report.regular_triangles, 0u);
      const auto decoded = prm::codec::decode(r.stream.data(), r.stream.size());
      ASSERT_TRUE(decoded.ok()) << decoded.status.message;
      EXPECT_EQ(prm::pipeline::count_zero_area_triangles(decoded.value), 0u);
      const prm::remesh::PrmMesh& prm = r.remesh.prm;
      ASSERT_EQ(decoded.value.num_vertices(), prm.mesh.positions.size());
      ASSERT_EQ(decoded.value.num_triangles(), prm.mesh.triangles.size());
      for (size_t k = 0; k < decoded.value.num_vertices(); ++k)
        for (int a = 0; a < 3; ++a)
          ASSERT_EQ(decoded.value.quantized[3 * k + static_cast<size_t>(a)],
                    static_cast<uint32_t>(prm.frame.quantize(prm.mesh.positions[r.report.vertex_order[k]][a], a)));
      for (size_t t = 0; t < decoded.value.num_triangles(); ++t) {
        const uint32_t in = r.report.triangle_order[t], rot = r.report.triangle_rotation[t];
        for (uint32_t c = 0; c < 3; ++c)
          ASSERT_EQ(r.report.vertex_order[decoded.value.triangles[3 * t + c]], prm.mesh.triangles[in][(rot + c) % 3]);
      }
      std::printf("%s g/diag %.3f: n_r %zu (quantization collapsed %zu triangles and %zu vertices, %zu moved), "
                  "%u/%zu regular, %zu bytes (%.2f bpv)\n",
                  std::filesystem::path(path).filename().c_str(), fraction, prm.mesh.positions.size(),
                  prm.stats.quantized_degenerate, prm.stats.quantized_coincident, prm.stats.quantized_moves,
                  r.report.regular_triangles, prm.mesh.triangles.size(), r.stream.size(),
                  8.0 * static_cast<double>(r.stream.size()) / static_cast<double>(prm.mesh.positions.size()));
    }
  }
}

}  // namespace
