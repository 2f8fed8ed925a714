#include "draco_codec.h"

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <vector>

namespace prm::bench {
namespace {

class DracoRun : public CodecRun {
 public:
  DracoRun(std::unique_ptr<draco::Mesh> input, int speed, int bits, std::optional<DracoGrid> grid)
      : input_(std::move(input)), speed_(speed), bits_(bits), grid_(grid) {}

  bool encode() override {
    draco::Encoder encoder;
    if (grid_)
      encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, bits_, 3, grid_->origin.data(),
                                               grid_->range);
    else
      encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits_);
    encoder.SetSpeedOptions(speed_, speed_);
    encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(*input_, &buffer);
    if (!status.ok()) {
      failure_ = "Draco encoder: " + status.error_msg_string();
      return false;
    }
    stream_.assign(buffer.data(), buffer.data() + buffer.size());
    return true;
  }

  size_t stream_bytes() const override { return stream_.size(); }

  bool decode() override {
    draco::DecoderBuffer buffer;
    buffer.Init(stream_.data(), stream_.size());
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) {
      failure_ = "Draco decoder: " + result.status().error_msg_string();
      return false;
    }
    decoded_ = std::move(result).value();
    return true;
  }

  Mesh decoded_mesh() const override {
    Mesh m;
    if (!decoded_) return m;
    const draco::PointAttribute* att = decoded_->GetNamedAttribute(draco::GeometryAttribute::POSITION);
    if (!att) return m;
    m.positions.resize(decoded_->num_points());
    for (draco::PointIndex p(0); p < decoded_->num_points(); ++p) {
      float v[3] = {0, 0, 0};
      att->ConvertValue<float>(att->mapped_index(p), 3, v);
      m.positions[p.value()] = {v[0], v[1], v[2]};
    }
    m.triangles.resize(decoded_->num_faces());
    for (draco::FaceIndex f(0); f < decoded_->num_faces(); ++f) {
      const draco::Mesh::Face& face = decoded_->face(f);
      m.triangles[f.value()] = {face[0].value(), face[1].value(), face[2].value()};
    }
    return m;
  }

 private:
  std::unique_ptr<draco::Mesh> input_;
  int speed_;
  int bits_;
  std::optional<DracoGrid> grid_;
  std::vector<char> stream_;
  std::unique_ptr<draco::Mesh> decoded_;
};

}  // namespace

std::unique_ptr<CodecRun> DracoCodec::start(const Mesh& mesh, std::string* why) const {
  if (mesh.triangles.empty()) {
    if (why) *why = "no triangles";
    return nullptr;
  }
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(static_cast<int>(mesh.num_faces()));
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    float corner[3][3];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) corner[k][c] = static_cast<float>(mesh.positions[mesh.triangles[f][k]][c]);
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(static_cast<uint32_t>(f)), corner[0], corner[1],
                                      corner[2]);
  }
  std::unique_ptr<draco::Mesh> input = builder.Finalize();
  if (!input) {
    if (why) *why = "draco::TriangleSoupMeshBuilder::Finalize failed";
    return nullptr;
  }
  return std::make_unique<DracoRun>(std::move(input), 10 - level_, bits_, grid_);
}

}  // namespace prm::bench
