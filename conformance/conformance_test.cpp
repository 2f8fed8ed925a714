// Runs every conformance vector (conformance/README.md): each valid stream decodes to exactly its expected.txt, and
// re-encoding that mesh gives a stream that decodes to it again; each invalid stream is rejected with its error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "prm/codec.h"
#include "test_meshes.h"

namespace {

namespace fs = std::filesystem;
using namespace prm::codec;

std::vector<uint8_t> read_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The value of "key": "value" in a flat JSON object (the vectors' vector.json).
std::string json_field(const std::string& json, const std::string& key) {
  const size_t k = json.find("\"" + key + "\"");
  if (k == std::string::npos) return "";
  const size_t a = json.find('"', json.find(':', k) + 1), b = json.find('"', a + 1);
  return json.substr(a + 1, b - a - 1);
}

// The number after "key": in a flat JSON object, or `otherwise`.
uint64_t json_number(const std::string& json, const std::string& key, uint64_t otherwise) {
  const size_t k = json.find("\"" + key + "\"");
  if (k == std::string::npos) return otherwise;
  return std::stoull(json.substr(json.find(':', k) + 1));
}

std::vector<fs::path> folders(const char* kind) {
  std::vector<fs::path> out;
  const fs::path root = fs::path(PRM_CONFORMANCE_DIR) / kind;
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Conformance, ValidStreamsDecodeExactly) {
  const auto dirs = folders("vectors");
  ASSERT_GE(dirs.size(), 9u);
  for (const fs::path& d : dirs) {
    SCOPED_TRACE(d.filename().string());
    const std::vector<uint8_t> stream = read_bytes(d / "stream.prm");
    ASSERT_FALSE(stream.empty());
    EXPECT_EQ(json_field(read_text(d / "vector.json"), "expect"), "decode");
    DecodeOptions opt;
    opt.positions = PositionOutput::quantized_only;
    const auto dec = decode(stream.data(), stream.size(), opt);
    ASSERT_TRUE(dec.ok()) << dec.status.message << " (§" << dec.status.spec_section << ")";
    const DecodedMesh& m = dec.value;
    // expected.txt: the frame line, then "v" and "f" lines.
    std::istringstream in(read_text(d / "expected.txt"));
    std::vector<uint32_t> q, tris;
    // The frame line, byte for byte as README.md specifies it (printf "%.17g" of each double).
    char frame[256];
    std::snprintf(frame, sizeof frame, "frame bits %d origin %.17g %.17g %.17g step %.17g", m.frame.bits,
                  m.frame.origin[0], m.frame.origin[1], m.frame.origin[2], m.frame.step);
    int frames = 0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream l(line);
      std::string tag;
      l >> tag;
      if (tag == "frame") {
        EXPECT_EQ(line, frame);
        ++frames;
      } else if (tag == "v" || tag == "f") {
        uint32_t a, b, c;
        l >> a >> b >> c;
        auto& dst = tag == "v" ? q : tris;
        dst.insert(dst.end(), {a, b, c});
      }
    }
    EXPECT_EQ(frames, 1);
    EXPECT_EQ(m.quantized, q);
    EXPECT_EQ(m.triangles, tris);
    const std::string json = read_text(d / "vector.json");
    char hash[32];
    std::snprintf(hash, sizeof hash, "0x%016llx",
                  static_cast<unsigned long long>(prm::codec::test::fnv1a64_words(m.quantized,
                                                                                  prm::codec::test::fnv1a64_words(m.triangles))));
    EXPECT_EQ(json_field(json, "fnv1a64"), hash);
    // Today's encoder, given the decoded mesh, writes a stream that decodes to the same mesh.
    const auto again = encode_quantized(m.quantized.data(), m.num_vertices(), m.triangles.data(), m.num_triangles(),
                                        m.frame);
    ASSERT_TRUE(again.ok()) << again.status.message;
    const auto back = decode(again.value.data(), again.value.size(), opt);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(back.value.num_vertices(), m.num_vertices());
  }
}

TEST(Conformance, InvalidStreamsAreRejected) {
  const auto dirs = folders("invalid");
  ASSERT_GE(dirs.size(), 56u);
  for (const fs::path& d : dirs) {
    SCOPED_TRACE(d.filename().string());
    const std::vector<uint8_t> stream = read_bytes(d / "stream.prm");
    const std::string json = read_text(d / "vector.json");
    EXPECT_EQ(json_field(json, "expect"), "error");
    // §4.1 The caller limits the vector asks for (count_exceeds_limit), else the defaults.
    DecodeOptions opt;
    opt.limits.max_vertices = json_number(json, "max_vertices", opt.limits.max_vertices);
    opt.limits.max_triangles = json_number(json, "max_triangles", opt.limits.max_triangles);
    const auto dec = decode(stream.data(), stream.size(), opt);
    ASSERT_FALSE(dec.ok());
    // The error name is what §4.4 and §11 require; the offset and section a decoder cites are only a SHOULD.
    EXPECT_EQ(std::string(error_name(dec.status.error)), json_field(json, "error"));
    // The reference decoder also rejects it where the vector says: in the container, or in the section whose
    // payload holds the reported offset (so that a change to the decoder cannot make a vector miss its check).
    const std::string where = json_field(json, "rejected_in");
    if (!where.empty()) {
      std::string in = "container";
      const auto info = inspect(stream.data(), stream.size());
      if (info.ok())
        for (const auto& sec : info.value.sections)
          if (dec.status.byte_offset >= sec.offset && dec.status.byte_offset <= sec.offset + sec.size)
            in = "section " + std::to_string(sec.id) + " (" + sec.name + ")";
      EXPECT_EQ(in, where) << dec.status.message;
    }
  }
}

// What the vectors cover (README.md): every error name of §4.4, all six relief axes of §8.1, the tap sets of §9.7.1
// that real streams enable, and a PRM stream whose frame has a non-zero origin and a non-unit step.
TEST(Conformance, Coverage) {
  std::set<std::string> errors;
  for (const fs::path& d : folders("invalid")) errors.insert(json_field(read_text(d / "vector.json"), "error"));
  for (const char* e : {"truncated", "bad_magic", "unsupported_version", "crc_mismatch", "bad_header", "bad_section",
                        "unsupported_feature", "count_exceeds_limit", "count_exceeds_stream", "bad_connectivity",
                        "non_manifold_result", "bad_position", "trailing_bytes"})
    EXPECT_EQ(errors.count(e), 1u) << e;
  std::set<int> axes, sets;
  bool frame = false;
  for (const fs::path& d : folders("vectors")) {
    const std::string json = read_text(d / "vector.json");
    const size_t a = json.find("\"regular_triangles_per_axis\"");
    if (a == std::string::npos) continue;
    std::istringstream counts(json.substr(json.find('[', a) + 1));
    for (int k = 0; k < 6; ++k) {
      uint64_t n = 0;
      char comma;
      counts >> n;
      if (k < 5) counts >> comma;
      if (n > 0) axes.insert(k);
    }
    for (const char* key : {"\"tap_sets_fitted\"", "\"tap_sets_default\""}) {
      const size_t t = json.find(key);
      if (t == std::string::npos) continue;
      std::istringstream list(json.substr(json.find('[', t) + 1, json.find(']', t) - json.find('[', t) - 1));
      for (std::string x; std::getline(list, x, ',');) sets.insert(std::stoi(x));
    }
    std::istringstream e(read_text(d / "expected.txt"));
    for (std::string line; std::getline(e, line);)
      if (line.rfind("frame ", 0) == 0)
        frame = frame || (line.find("origin 0 0 0 ") == std::string::npos && line.find(" step 1") == std::string::npos);
  }
  EXPECT_EQ(axes.size(), 6u);
  for (int s : {0, 20, 21, 22, 23, 25, 26, 27, 28, 29, 31, 32, 35}) EXPECT_EQ(sets.count(s), 1u) << "tap set " << s;
  EXPECT_TRUE(frame);
}

}  // namespace
