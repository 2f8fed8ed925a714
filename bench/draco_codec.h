// Draco 1.5.5 as a column of the codec table (codec_table.h): edgebreaker, positions only, 12-bit quantization,
// compression level 0..10 (Draco's speed options are 10 − level, for encoder and decoder alike).
// Only Draco's core codec headers are used here, never draco/io (ECOSYSTEM.md §2.3: Draco's glTF reader embeds
// its own tinygltf, which must not meet ours).
#pragma once

#include <memory>
#include <string>

#include "codec_table.h"

namespace prm::bench {

class DracoCodec : public Codec {
 public:
  explicit DracoCodec(int level, int quantization_bits = 12) : level_(level), bits_(quantization_bits) {}
  std::string name() const override { return "Draco L" + std::to_string(level_); }
  // Builds the draco::Mesh with draco::TriangleSoupMeshBuilder (one float position per corner; Draco's finalizer
  // merges equal positions back into shared points).
  std::unique_ptr<CodecRun> start(const Mesh& mesh, std::string* why) const override;

 private:
  int level_;
  int bits_;
};

}  // namespace prm::bench
