// prm_conformance_generate OUT_DIR [--only-prm-1.1]: writes the conformance vectors (conformance/README.md) from
// the codec's test meshes with today's reference encoder. Never run by CI: vectors are generated once and kept
// forever (a format change adds vectors, it does not rewrite them). The 1.1 PRM vector was written by this program
// built at commit c1b6f19 (the last 1.1 encoder) with --only-prm-1.1.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "prm/codec.h"
#include "test_meshes.h"

namespace {

using namespace prm::codec;
using namespace prm::codec::test;
namespace fs = std::filesystem;

void write_bytes(const fs::path& p, const std::vector<uint8_t>& b) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// A valid vector: the stream, its exact decoded mesh (expected.txt) and vector.json.
void valid(const fs::path& dir, const std::string& name, const std::vector<uint8_t>& stream, const char* format,
           const char* feature, const char* sections) {
  const fs::path d = dir / "vectors" / name;
  fs::create_directories(d);
  write_bytes(d / "stream.prm", stream);
  DecodeOptions opt;
  opt.positions = PositionOutput::quantized_only;
  const auto dec = decode(stream.data(), stream.size(), opt);
  if (!dec.ok()) {
    std::fprintf(stderr, "%s does not decode: %s\n", name.c_str(), dec.status.message.c_str());
    std::exit(1);
  }
  const DecodedMesh& m = dec.value;
  std::ofstream e(d / "expected.txt");
  char buf[256];
  std::snprintf(buf, sizeof buf, "frame bits %d origin %.17g %.17g %.17g step %.17g\n", m.frame.bits, m.frame.origin[0],
                m.frame.origin[1], m.frame.origin[2], m.frame.step);
  e << "# the exact decoded mesh of stream.prm: vertices (quantized coordinates) and triangles in spec order (6.6)\n"
    << buf;
  for (size_t v = 0; v < m.num_vertices(); ++v)
    e << "v " << m.quantized[3 * v] << ' ' << m.quantized[3 * v + 1] << ' ' << m.quantized[3 * v + 2] << '\n';
  for (size_t t = 0; t < m.num_triangles(); ++t)
    e << "f " << m.triangles[3 * t] << ' ' << m.triangles[3 * t + 1] << ' ' << m.triangles[3 * t + 2] << '\n';
  std::ofstream j(d / "vector.json");
  const uint64_t hash = fnv1a64_words(m.quantized, fnv1a64_words(m.triangles));
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(hash));
  j << "{\n  \"expect\": \"decode\",\n  \"format\": \"" << format << "\",\n  \"feature\": \"" << feature
    << "\",\n  \"spec_sections\": [" << sections << "],\n  \"bytes\": " << stream.size()
    << ",\n  \"vertices\": " << m.num_vertices() << ",\n  \"triangles\": " << m.num_triangles()
    << ",\n  \"fnv1a64\": \"" << buf << "\"\n}\n";
  std::printf("%-40s %6zu bytes, %zu vertices, %zu triangles\n", name.c_str(), stream.size(), m.num_vertices(),
              m.num_triangles());
}

// An invalid vector: the stream and the error a decoder must report.
void invalid(const fs::path& dir, const std::string& name, const std::vector<uint8_t>& stream, const char* error,
             const char* section, const char* what) {
  const fs::path d = dir / "invalid" / name;
  fs::create_directories(d);
  write_bytes(d / "stream.prm", stream);
  const auto dec = decode(stream.data(), stream.size());
  if (dec.ok() || std::strcmp(error_name(dec.status.error), error) != 0) {
    std::fprintf(stderr, "%s: expected %s, got %s\n", name.c_str(), error,
                 dec.ok() ? "a mesh" : error_name(dec.status.error));
    std::exit(1);
  }
  std::ofstream j(d / "vector.json");
  j << "{\n  \"expect\": \"error\",\n  \"error\": \"" << error << "\",\n  \"spec_section\": \"" << section
    << "\",\n  \"what\": \"" << what << "\"\n}\n";
  std::printf("%-40s %6zu bytes -> %s\n", name.c_str(), stream.size(), error);
}

std::vector<uint8_t> general(const TestMesh& m, int bits, int seam_context = 0) {
  EncodeOptions o;
  o.position_bits = bits;
  o.seam_context = seam_context;  // the 1.0 vectors were written before format 1.3's seam context
  return encode(m.xyz.data(), m.num_vertices(), m.triangles.data(), m.num_triangles(), o).value;
}

int64_t bumpy_top(int i, int j, const void*) {
  return 2000 + std::lround(90 * std::sin(0.3 * i) * std::cos(0.2 * j) + 3 * i);
}
int64_t bumpy_bottom(int i, int j, const void*) { return 1000 - std::lround(40 * std::cos(0.25 * i + 0.1 * j)); }

std::vector<uint8_t> pillow_stream(int r, int perturb, int depth, uint32_t seed = 1, int seam_context = 0,
                                   bool patch_contexts = false) {
  std::vector<std::array<int, 2>> moved;
  uint32_t x = seed;
  for (int k = 0; k < perturb; ++k) {  // a small LCG: the same points on every platform
    x = x * 1103515245u + 12345u;
    const int i = static_cast<int>((x >> 8) % static_cast<uint32_t>(r)) - r / 2;
    x = x * 1103515245u + 12345u;
    const int j = static_cast<int>((x >> 8) % static_cast<uint32_t>(r)) - r / 2;
    moved.push_back({i, j});
  }
  const QuantizedMesh m = lattice_pillow(r, 8, bumpy_top, bumpy_bottom, nullptr, moved);
  Frame f;
  f.bits = 12;
  f.origin = {0, 0, 0};
  f.step = 1;
  PrmOptions o;
  o.grid = 8;
  o.height_depth = depth;
  o.seam_context = seam_context;
  o.patch_contexts = patch_contexts;  // the vectors before 1.4 were written without format 1.4's patch contexts
  return encode_prm(m.q.data(), m.nv(), m.tris.data(), m.nt(), f, o).value;
}

void fix_crc(std::vector<uint8_t>& s) {  // CRC-32 (spec 3.5), bitwise
  uint32_t c = 0xFFFFFFFFu;
  for (size_t i = 0; i + 4 < s.size(); ++i) {
    c ^= s[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1)));
  }
  c ^= 0xFFFFFFFFu;
  for (int i = 0; i < 4; ++i) s[s.size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR [--only-prm-1.1 | --only-1.3 | --only-1.4]\n", argv[0]);
    return 1;
  }
  const fs::path dir = argv[1];
  if (argc > 2 && std::string(argv[2]) == "--only-prm-1.1") {
    valid(dir, "010-prm-1.1-pillow", pillow_stream(4, 3, -1, 5), "1.1",
          "PRM stream of format 1.1: LERS without valence context, difference patches", "\"7.2\", \"8.3\", \"9.3\"");
    return 0;
  }
  // Each format's vectors were added without touching the older ones; --only-1.N writes only those of 1.N.
  const bool only_13 = argc > 2 && std::string(argv[2]) == "--only-1.3";
  const bool only_14 = argc > 2 && std::string(argv[2]) == "--only-1.4";
  // Format 1.4 (§8.4.1 base references, §9.7.4 sign contexts).
  if (!only_13) {
    valid(dir, "016-prm-1.4-patch-contexts", pillow_stream(12, 40, 7, 7, -1, true), "1.4",
          "PRM stream with the patch contexts (Flags bit 3): bases from their references, sign contexts, linear "
          "prediction, many off-lattice vertices",
          "\"3.3\", \"8.4.1\", \"9.7.4\"");
    valid(dir, "017-prm-1.4-patch-contexts-depth3", pillow_stream(12, 40, 3, 7, -1, true), "1.4",
          "the patch contexts with difference patches of depth 3: bases from their references", "\"8.4.1\", \"9.3\"");
  }
  if (only_14) return 0;
  // Format 1.3 (§6.5.2 the seam context).
  valid(dir, "006-general-1.3-seam-context",
        general(concat({sphere_with_holes(2, 3), plate_with_holes(2, 1), icosphere(2)}), 12, 1), "1.3",
        "the CLERS seam context (Flags bit 2) on a general-path stream: holes, a handle, irregular and regular vertices",
        "\"3.2\", \"3.3\", \"6.5.2\"");
  valid(dir, "015-prm-1.3-seam-context", pillow_stream(12, 9, 7, 3, 1), "1.3",
        "PRM stream with the CLERS seam context, linear prediction, off-lattice vertices", "\"6.5.2\", \"9.7.4\"");
  if (only_13) return 0;
  valid(dir, "001-tetrahedron", general(tetrahedron(), 12), "1.0", "the worked example of 3.6 and 6.9",
        "\"3.6\", \"6.9\"");
  valid(dir, "002-genus1-plate", general(plate_with_holes(1, 1), 12), "1.0", "handle events, genus 1", "\"6.4.6\"");
  valid(dir, "003-holes", general(sphere_with_holes(1, 2), 10), "1.0", "two holes closed by dummy vertices, 10 bits",
        "\"6.7\"");
  valid(dir, "004-components", general(concat({tetrahedron(), plate_with_holes(1, 1), single_triangle(), hex_patch(2, false)}), 16),
        "1.0", "four components, a boundary, 16 bits", "\"6.3\", \"6.4.7\"");
  valid(dir, "005-icosphere", general(icosphere(3), 12), "1.0", "a regular mesh: CLERS almost all C", "\"6.5\"");
  valid(dir, "011-prm-1.2-difference-depth3", pillow_stream(4, 3, 3, 5), "1.2",
        "PRM stream: valence context, difference patches of depth 3, off-lattice vertices",
        "\"7.3\", \"9.1\", \"9.2\", \"9.3\", \"10.2\"");
  valid(dir, "012-prm-1.2-difference-depth0", pillow_stream(6, 0, 0), "1.2", "difference patches of depth 0",
        "\"9.3\", \"9.4\"");
  valid(dir, "013-prm-1.2-prediction", pillow_stream(12, 0, 7), "1.2",
        "linear prediction with fitted weights (Height_Depth 7)", "\"9.7.2\", \"9.7.3\", \"9.7.4\"");
  valid(dir, "014-prm-1.2-prediction-offlattice", pillow_stream(12, 9, 7, 3), "1.2",
        "linear prediction, placed and off-lattice vertices", "\"9.7.4\", \"10.2\"");
  // Invalid streams: each breaks one rule of the container.
  const std::vector<uint8_t> good = pillow_stream(4, 3, 7, 5);
  {
    std::vector<uint8_t> s(good.begin(), good.end() - 9);
    invalid(dir, "100-truncated", s, "crc_mismatch", "3.5", "the last 9 bytes are missing");
  }
  {
    std::vector<uint8_t> s = good;
    s[s.size() - 1] ^= 0x40;
    invalid(dir, "101-crc", s, "crc_mismatch", "3.5", "one bit of the CRC flipped");
  }
  {
    std::vector<uint8_t> s = good;
    s[0] = 'Q';
    invalid(dir, "102-magic", s, "bad_magic", "3.1", "the magic's first byte");
  }
  {
    std::vector<uint8_t> s = good;
    s[4] = 2;
    fix_crc(s);
    invalid(dir, "103-major-version", s, "unsupported_version", "3.2", "Version_Major 2");
  }
  {
    std::vector<uint8_t> s = good;
    s[6] |= 0x02;
    fix_crc(s);
    invalid(dir, "104-reserved-flag", s, "unsupported_feature", "3.3", "Flags bit 1");
  }
  {
    std::vector<uint8_t> s(good.begin(), good.begin() + 4);
    invalid(dir, "105-short", s, "truncated", "3.1", "a stream of 4 bytes");
  }
  return 0;
}
