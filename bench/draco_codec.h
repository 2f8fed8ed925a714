// Draco 1.5.5 as a column of the codec table (codec_table.h): edgebreaker, positions only, 12-bit quantization,
// compression level 0..10 (Draco's speed options are 10 − level, for encoder and decoder alike).
// Only Draco's core codec headers are used here, never draco/io (ECOSYSTEM.md §2.3: Draco's glTF reader embeds
// its own tinygltf, which must not meet ours).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "codec_table.h"

namespace prm::bench {

// Draco's explicit quantization grid (draco::Encoder::SetAttributeExplicitQuantization): step = range / (2^bits - 1)
// from origin, instead of the mesh's bounding box. The Table 1 bench gives Draco our stream's own frame, so that at
// the same bits Draco quantizes the decoded PRM onto the very grid its positions lie on.
struct DracoGrid {
  std::array<float, 3> origin{0, 0, 0};
  float range = 1;
};

class DracoCodec : public Codec {
 public:
  explicit DracoCodec(int level, int quantization_bits = 12, std::optional<DracoGrid> grid = std::nullopt)
      : level_(level), bits_(quantization_bits), grid_(grid) {}
  std::string name() const override { return "Draco L" + std::to_string(level_); }
  // Builds the draco::Mesh with draco::TriangleSoupMeshBuilder (one float position per corner; Draco's finalizer
  // merges equal positions back into shared points).
  std::unique_ptr<CodecRun> start(const Mesh& mesh, std::string* why) const override;

 private:
  int level_;
  int bits_;
  std::optional<DracoGrid> grid_;
};

}  // namespace prm::bench
