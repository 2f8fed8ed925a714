// Runs every conformance vector (conformance/README.md): each valid stream decodes to exactly its expected.txt, and
// re-encoding that mesh gives a stream that decodes to it again; each invalid stream is rejected with its error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
    int bits = 0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream l(line);
      std::string tag;
      l >> tag;
      if (tag == "frame") {
        std::string k;
        l >> k >> bits;
      } else if (tag == "v" || tag == "f") {
        uint32_t a, b, c;
        l >> a >> b >> c;
        auto& dst = tag == "v" ? q : tris;
        dst.insert(dst.end(), {a, b, c});
      }
    }
    EXPECT_EQ(m.frame.bits, bits);
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
  ASSERT_GE(dirs.size(), 6u);
  for (const fs::path& d : dirs) {
    SCOPED_TRACE(d.filename().string());
    const std::vector<uint8_t> stream = read_bytes(d / "stream.prm");
    const std::string json = read_text(d / "vector.json");
    EXPECT_EQ(json_field(json, "expect"), "error");
    const auto dec = decode(stream.data(), stream.size());
    ASSERT_FALSE(dec.ok());
    // The error name is what §4.4 requires; the section a decoder cites is only a SHOULD.
    EXPECT_EQ(std::string(error_name(dec.status.error)), json_field(json, "error"));
  }
}

}  // namespace
