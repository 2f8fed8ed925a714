// prm_conformance_generate OUT_DIR [--only-prm-1.1]: writes the conformance vectors (conformance/README.md) from
// the codec's test meshes with today's reference encoder. Never run by CI: vectors are generated once and kept
// forever (a format change adds vectors, it does not rewrite them). The 1.1 PRM vector was written by this program
// built at commit c1b6f19 (the last 1.1 encoder) with --only-prm-1.1.
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "height_prediction_shared.h"  // codec/src: the predictor table a stream enables (§9.7.2), for vector.json
#include "prm/codec.h"
#include "range_decoder.h"
#include "range_encoder.h"
#include "signed_int_model.h"
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
           const char* feature, const char* sections, const std::string& extra = "") {
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
    << ",\n  \"fnv1a64\": \"" << buf << "\"" << extra << "\n}\n";
  std::printf("%-40s %6zu bytes, %zu vertices, %zu triangles\n", name.c_str(), stream.size(), m.num_vertices(),
              m.num_triangles());
}

// The sections of a stream whose container is valid: (id, payload offset, payload size); empty if it is not.
std::vector<std::array<uint64_t, 3>> section_ranges(const std::vector<uint8_t>& stream) {
  std::vector<std::array<uint64_t, 3>> out;
  const auto info = inspect(stream.data(), stream.size());
  if (info.ok())
    for (const auto& sec : info.value.sections) out.push_back({sec.id, sec.offset, sec.size});
  return out;
}

// Where our decoder rejected a stream: the section whose payload holds the error's byte offset, or the container.
std::string rejected_in(const std::vector<uint8_t>& stream, uint64_t offset) {
  static const char* names[] = {"", "connectivity", "positions", "irregular_triangles", "patches"};
  for (const auto& r : section_ranges(stream))
    if (offset >= r[1] && offset <= r[1] + r[2] && r[0] <= 4)
      return "section " + std::to_string(r[0]) + " (" + names[r[0]] + ")";
  return "container";
}

// An invalid vector: the stream, the error a decoder must report (§4.4), the spec section whose rule it breaks
// (what our decoder cites), where it is rejected (checked against the decoder's byte offset: the container or the
// section that must reject it) and, for count_exceeds_limit, the caller limits (§4.1) a runner passes.
void invalid(const fs::path& dir, const std::string& name, const std::vector<uint8_t>& stream, const char* error,
             const char* section, const char* what, const char* where = nullptr, const DecodeLimits* limits = nullptr) {
  DecodeOptions opt;
  if (limits) opt.limits = *limits;
  const auto dec = decode(stream.data(), stream.size(), opt);
  const std::string in = dec.ok() ? "" : rejected_in(stream, dec.status.byte_offset);
  // The older vectors (no `where`) were checked by their error name only.
  if (dec.ok() || std::strcmp(error_name(dec.status.error), error) != 0 ||
      (where && (std::strcmp(dec.status.spec_section, section) != 0 || in != where))) {
    std::fprintf(stderr, "%s: expected %s (§%s) in %s, got %s (§%s) in %s: %s\n", name.c_str(), error, section,
                 where ? where : "-", dec.ok() ? "a mesh" : error_name(dec.status.error), dec.status.spec_section,
                 in.c_str(), dec.status.message.c_str());
    std::exit(1);
  }
  const fs::path d = dir / "invalid" / name;
  fs::create_directories(d);
  write_bytes(d / "stream.prm", stream);
  std::ofstream j(d / "vector.json");
  j << "{\n  \"expect\": \"error\",\n  \"error\": \"" << error << "\",\n  \"spec_section\": \"" << section
    << "\",\n  \"what\": \"" << what << "\"";
  if (where) j << ",\n  \"rejected_in\": \"" << where << "\"";
  if (limits)
    j << ",\n  \"limits\": {\"max_vertices\": " << limits->max_vertices
      << ", \"max_triangles\": " << limits->max_triangles << "}";
  j << "\n}\n";
  std::printf("%-40s %6zu bytes -> %s (§%s) in %s\n", name.c_str(), stream.size(), error, section, in.c_str());
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

// Format 1.5 (§8.4.2): two pillows side by side, the first on grid size 8 (Grid_Size), the second on grid size 6
// (Extra_Grid[1]) moved along x by 30 of its lattice steps (so its vertices stay on its lattice), in one stream.
std::vector<uint8_t> two_grid_stream(int depth) {
  std::vector<std::array<int, 2>> moved = {{1, -2}, {-3, 2}};
  const QuantizedMesh a = lattice_pillow(6, 8, bumpy_top, bumpy_bottom, nullptr, moved);
  const QuantizedMesh b = lattice_pillow(5, 6, bumpy_top, bumpy_bottom, nullptr, moved);
  QuantizedMesh m = a;
  const uint32_t base = static_cast<uint32_t>(a.nv());
  for (size_t v = 0; v < b.nv(); ++v) m.q.insert(m.q.end(), {b.q[3 * v] + 6 * 30, b.q[3 * v + 1], b.q[3 * v + 2]});
  for (uint32_t t : b.tris) m.tris.push_back(t + base);
  Frame f;
  f.bits = 12;
  f.origin = {0, 0, 0};
  f.step = 1;
  PrmOptions o;
  o.grid = 8;
  o.extra_grids = {6};
  o.height_depth = depth;
  o.seam_context = 0;
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

void put_varint(std::vector<uint8_t>& b, uint32_t v) {  // §1.3
  for (; v >= 0x80; v >>= 7) b.push_back(static_cast<uint8_t>(v | 0x80));
  b.push_back(static_cast<uint8_t>(v));
}

// A valid stream taken apart (§3): its header fields and section payloads, to change one thing and put it back
// together with a valid CRC, so that the defect reaches the check that must find it.
struct Parts {
  uint8_t major = 1, minor = 0, flags = 0, bits = 12;
  uint32_t vertices = 0, triangles = 0;
  std::array<double, 3> origin{};
  double step = 1;
  std::array<uint32_t, 3> bbox_min{}, bbox_extent{};
  std::vector<std::pair<uint8_t, std::vector<uint8_t>>> sections;
  std::vector<uint8_t>& payload(uint8_t id) {
    for (auto& sec : sections)
      if (sec.first == id) return sec.second;
    std::fprintf(stderr, "no section %d\n", id);
    std::exit(1);
  }
};

Parts split(const std::vector<uint8_t>& s) {
  const auto info = inspect(s.data(), s.size());
  if (!info.ok()) std::exit(1);
  const StreamInfo& i = info.value;
  Parts p;
  p.major = i.version_major;
  p.minor = i.version_minor;
  p.flags = i.flags;
  p.bits = static_cast<uint8_t>(i.frame.bits);
  p.vertices = i.vertices;
  p.triangles = i.triangles;
  for (int k = 0; k < 3; ++k) {
    p.origin[k] = i.frame.origin[k];
    p.bbox_min[k] = i.bbox_min[k];
    p.bbox_extent[k] = i.bbox_max[k] - i.bbox_min[k];
  }
  p.step = i.frame.step;
  for (const auto& sec : i.sections)
    p.sections.push_back({sec.id, std::vector<uint8_t>(s.begin() + static_cast<std::ptrdiff_t>(sec.offset),
                                                       s.begin() + static_cast<std::ptrdiff_t>(sec.offset + sec.size))});
  return p;
}

void put_f64(std::vector<uint8_t>& b, double d) {
  uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<uint8_t>(bits >> (8 * i)));
}

// Magic, version and header (§3.1-§3.3).
std::vector<uint8_t> head(const Parts& p) {
  std::vector<uint8_t> b = {'P', 'R', 'M', 0x1A, p.major, p.minor, p.flags, p.bits};
  put_varint(b, p.vertices);
  put_varint(b, p.triangles);
  for (double o : p.origin) put_f64(b, o);
  put_f64(b, p.step);
  for (uint32_t m : p.bbox_min) put_varint(b, m);
  for (uint32_t e : p.bbox_extent) put_varint(b, e);
  return b;
}

// The stream of `p` with a valid CRC (§3.4, §3.5).
std::vector<uint8_t> join(const Parts& p) {
  std::vector<uint8_t> b = head(p);
  for (const auto& sec : p.sections) {
    b.push_back(sec.first);
    put_varint(b, static_cast<uint32_t>(sec.second.size()));
    b.insert(b.end(), sec.second.begin(), sec.second.end());
  }
  b.insert(b.end(), 4, 0);
  fix_crc(b);
  return b;
}

// Bytes followed by a valid CRC.
std::vector<uint8_t> with_crc(std::vector<uint8_t> b) {
  b.insert(b.end(), 4, 0);
  fix_crc(b);
  return b;
}

uint32_t get_varint(const std::vector<uint8_t>& b, size_t& i) {  // §1.3, of a valid stream
  uint32_t v = 0;
  for (int k = 0;; k += 7) {
    const uint8_t x = b[i++];
    v |= uint32_t{x & 0x7Fu} << k;
    if (!(x & 0x80)) return v;
  }
}

// A defect deep inside a range-coded block, where only decoding finds it: the first change, over the payload bytes
// of section `id` from `from` on and the XOR values 1..255 in order, whose stream (CRC valid) our decoder rejects
// with `error` at §`sec`, with a message containing `has`, at least 8 bytes before the block's end (so that the
// defect is met before the block runs out; a defect met in a later section is taken as it is). `what` gets the
// change.
std::vector<uint8_t> mutate(const std::vector<uint8_t>& good, uint8_t id, size_t from, const char* error,
                            const char* sec, const char* has, std::string& what, std::string* cited = nullptr,
                            bool required = true) {
  Parts p = split(good);
  std::vector<uint8_t>& pay = p.payload(id);
  const std::vector<uint8_t> orig = pay;
  uint64_t pay_offset = 0;
  for (const auto& r : section_ranges(good))
    if (r[0] == id) pay_offset = r[1];
  for (size_t i = from; i < pay.size(); ++i) {
    for (int x = 1; x < 256; ++x) {
      pay[i] = static_cast<uint8_t>(orig[i] ^ x);
      const std::vector<uint8_t> s = join(p);
      const auto dec = decode(s.data(), s.size());
      if (!dec.ok() && std::strcmp(error_name(dec.status.error), error) == 0 &&
          std::strncmp(dec.status.spec_section, sec, std::strlen(sec)) == 0 &&
          dec.status.message.find(has) != std::string::npos &&
          (dec.status.byte_offset < pay_offset || dec.status.byte_offset + 8 <= pay_offset + pay.size())) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "byte %zu of section %d XOR 0x%02X: ", i, id, x);
        what = buf + dec.status.message;
        if (cited) *cited = dec.status.spec_section;
        return s;
      }
    }
    pay[i] = orig[i];
  }
  if (!required) return {};
  std::fprintf(stderr, "no change of section %d gives %s (§%s, %s)\n", id, error, sec, has);
  std::exit(1);
}


// What a PRM stream exercises beyond its mesh, for vector.json: the relief axes of its regular triangles (§7.1's
// rule, on the decoded mesh with the stream's Grid_Size) and the tap sets its predictor table enables (§9.7.2).
std::string prm_features(const std::vector<uint8_t>& stream) {
  const auto info = inspect(stream.data(), stream.size());
  DecodeOptions opt;
  opt.positions = PositionOutput::quantized_only;
  const auto dec = decode(stream.data(), stream.size(), opt);
  const SectionInfo* patches = nullptr;
  for (const auto& sec : info.value.sections)
    if (sec.id == 4) patches = &sec;
  if (!dec.ok() || !patches) return "";
  RangeDecoder rc;
  rc.init(stream.data() + patches->offset, patches->size);
  const int64_t a0 = rc.decode_direct(21);  // §8.4 Grid_Size, Height_Depth
  const int depth = static_cast<int>(rc.decode_direct(3));
  std::vector<int64_t> grids = {a0};  // §8.4.2 the grid table (Flags bit 4)
  if (info.value.flags & 0x10) {
    const int n = static_cast<int>(rc.decode_direct(3));
    for (int k = 0; k < n; ++k) grids.push_back(rc.decode_direct(21));
  }
  std::string out;
  // §7.1 steps 1-3 on the decoded mesh (closed: no dummy vertices).
  const DecodedMesh& m = dec.value;
  const size_t nt = m.num_triangles();
  std::vector<int> axis(nt, -1);
  for (size_t g = 0; g < grids.size(); ++g) {
  // §8.1 B = floor(A / 2), C = floor((isqrt(3 A^2) + 1) / 2).
  const int64_t a = grids[g];
  int64_t root = static_cast<int64_t>(std::sqrt(3.0 * static_cast<double>(a) * static_cast<double>(a)));
  while (root * root > 3 * a * a) --root;
  while ((root + 1) * (root + 1) <= 3 * a * a) ++root;
  const int64_t b = a / 2, cc = (root + 1) / 2;
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3 && axis[t] < 0; ++k) {
      int64_t p[3][2];
      bool lattice = true;
      for (int r = 0; r < 3; ++r) {
        const uint32_t v = m.triangles[3 * t + r];
        const int64_t u = m.quantized[3 * v + (k + 1) % 3], w = m.quantized[3 * v + (k + 2) % 3];
        if (w % cc != 0 || (u - b * (w / cc)) % a != 0) lattice = false;
        p[r][1] = w / cc;
        p[r][0] = (u - b * p[r][1]) / a;
      }
      if (!lattice) continue;
      bool steps = true;
      for (int r = 0; r < 3; ++r) {
        const int64_t di = p[(r + 1) % 3][0] - p[r][0], dj = p[(r + 1) % 3][1] - p[r][1];
        const bool dir = (di == 1 && dj == 0) || (di == 0 && dj == 1) || (di == -1 && dj == 1) ||
                         (di == -1 && dj == 0) || (di == 0 && dj == -1) || (di == 1 && dj == -1);
        steps = steps && dir;
      }
      const int64_t x = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
      if (steps && (x == 1 || x == -1)) axis[t] = 6 * static_cast<int>(g) + 2 * k + (x == 1 ? 0 : 1);
    }
  }
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
  for (size_t t = 0; t < nt; ++t)
    for (int r = 0; r < 3; ++r) {
      const uint32_t u = m.triangles[3 * t + r], v = m.triangles[3 * t + (r + 1) % 3];
      edges[{std::min(u, v), std::max(u, v)}].push_back(t);
    }
  std::vector<int> final_axis = axis;
  for (const auto& e : edges)
    if (e.second.size() == 2 && axis[e.second[0]] >= 0 && axis[e.second[1]] >= 0 &&
        axis[e.second[0]] != axis[e.second[1]])
      final_axis[e.second[0]] = final_axis[e.second[1]] = -1;
  std::array<size_t, 6> count{};
  for (int x : final_axis)
    if (x >= 0) ++count[static_cast<size_t>(x % 6)];
  if (grids.size() > 1) {
    out += ",\n  \"grid_sizes\": [";
    for (size_t g = 0; g < grids.size(); ++g) out += (g ? ", " : "") + std::to_string(grids[g]);
    out += "]";
  }
  out += ",\n  \"grid_size\": " + std::to_string(a0) + ",\n  \"height_depth\": " + std::to_string(depth) +
         ",\n  \"regular_triangles_per_axis\": [";
  for (int k = 0; k < 6; ++k) out += (k ? ", " : "") + std::to_string(count[static_cast<size_t>(k)]);
  out += "]";
  if (depth == 7) {
    rc.decode_direct(3);  // Overlap_Depth
    LpTable table;
    std::array<bool, kLpSets> fitted{};
    LpModels models;
    auto direct = [&](int n, uint32_t) { return rc.decode_direct(n); };
    auto value = [&](SignedIntModel& sm, int max_class, int64_t, int64_t& v) { return decode_signed(rc, sm, max_class, v); };
    code_lp_table(table, fitted, models, direct, value);
    std::string fit, def;
    for (int t = 0; t < kLpSets; ++t) {
      if (!table.enabled[t]) continue;
      std::string& list = fitted[t] ? fit : def;
      list += (list.empty() ? "" : ", ") + std::to_string(t);
    }
    out += ",\n  \"tap_sets_fitted\": [" + fit + "],\n  \"tap_sets_default\": [" + def + "]";
  }
  return out;
}

// The invalid vectors of format 1.4 (§4.4): every error name, each reaching the check that must find it (a valid
// container and CRC, the defect inside the section), and the order of checks of §3.7 (each case a stream with two
// defects, named by the one met first).
void error_vectors(const fs::path& dir) {
  const std::vector<uint8_t> tetra = general(tetrahedron(), 12);  // the stream of §3.6
  const std::vector<uint8_t> ico = general(icosphere(2), 12);
  const std::vector<uint8_t> prm = pillow_stream(6, 3, 7, 5, -1, true);  // 1.4, linear prediction
  const char* kContainer = "container";
  const char* kS1 = "section 1 (connectivity)";
  const char* kS2 = "section 2 (positions)";
  const char* kS3 = "section 3 (irregular_triangles)";
  const char* kS4 = "section 4 (patches)";
  // §3.7 The order of checks of the container.
  invalid(dir, "106-magic-before-length", {'P', 'R', 'Q', 0x1A, 1, 4, 0, 12}, "bad_magic", "3.1",
          "8 bytes, the magic's third byte wrong: the magic is checked before the length", kContainer);
  invalid(dir, "107-version-before-length", {'P', 'R', 'M', 0x1A, 2, 0, 0, 12}, "unsupported_version", "3.2",
          "8 bytes, Version_Major 2: the version is checked before the length", kContainer);
  {
    std::vector<uint8_t> s = tetra;
    s[4] = 2;
    invalid(dir, "108-version-before-crc", s, "unsupported_version", "3.2",
            "Version_Major 2 and the CRC not updated: the version is checked before the CRC", kContainer);
  }
  invalid(dir, "109-short-for-crc", {'P', 'R', 'M', 0x1A, 1, 0, 0, 12, 4}, "truncated", "3.5",
          "9 bytes, magic and version valid: no room for the CRC", kContainer);
  {
    std::vector<uint8_t> s = tetra;
    s[6] |= 0x02;
    invalid(dir, "110-crc-before-header", s, "crc_mismatch", "3.5",
            "Flags bit 1 and the CRC not updated: the CRC is checked before the header", kContainer);
  }
  invalid(dir, "111-flags-before-truncated-header", with_crc({'P', 'R', 'M', 0x1A, 1, 4, 0x02, 12}),
          "unsupported_feature", "3.3", "Flags bit 1, then the header ends: each field is checked when read",
          kContainer);
  invalid(dir, "112-truncated-header", with_crc({'P', 'R', 'M', 0x1A, 1, 4, 0x09, 12, 4, 4, 0, 0}), "truncated",
          "3.3", "the stream (and its CRC) ends in Origin_X", kContainer);
  {
    std::vector<uint8_t> s = {'P', 'R', 'M', 0x1A, 1, 0, 0, 12, 0x84, 0x00, 4};
    invalid(dir, "113-malformed-varint-in-header", with_crc(s), "bad_section", "1.3",
            "Vertex_Count coded 84 00 (a redundant zero group), then the header ends", kContainer);
  }
  const Parts tp = split(tetra);
  const std::vector<uint8_t> th = head(tp);
  auto cat = [](std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  std::vector<uint8_t> sec1 = {1};
  put_varint(sec1, static_cast<uint32_t>(tp.sections[0].second.size()));
  sec1 = cat(sec1, tp.sections[0].second);
  invalid(dir, "114-section-id-before-length", with_crc(cat(th, {0x00, 0x80})), "bad_section", "3.4",
          "section id 0, then the stream ends in its length: the id is checked before the length is read",
          kContainer);
  invalid(dir, "115-reserved-section-before-length", with_crc(cat(cat(th, sec1), {0x07, 0x80})),
          "unsupported_feature", "3.4", "section 1, then reserved id 7 whose length is cut", kContainer);
  invalid(dir, "116-repeated-section-before-length", with_crc(cat(cat(th, sec1), {0x01, 0x80})), "bad_section",
          "3.4", "section 1 twice, the second's length cut", kContainer);
  {
    std::vector<uint8_t> s = cat(th, {0x01, 0x7F});
    invalid(dir, "117-section-longer-than-stream", with_crc(cat(s, tp.sections[0].second)), "truncated", "3.4",
            "section 1 claims 127 bytes, 8 remain", kContainer);
  }
  {
    Parts p = tp;
    std::swap(p.sections[0], p.sections[1]);
    invalid(dir, "118-sections-out-of-order", join(p), "bad_section", "3.4", "section 2 before section 1",
            kContainer);
  }
  {
    Parts p = tp;
    p.sections.pop_back();
    p.sections[0].second.pop_back();  // CLERS_Data of 3 bytes: count_exceeds_stream, were section 1 decoded
    invalid(dir, "119-section-missing-before-payload", join(p), "bad_section", "3.4",
            "no section 2, and section 1's CLERS_Data is 3 bytes: the container is checked before any payload",
            kContainer);
  }
  {
    Parts p = split(prm);
    p.sections.pop_back();
    invalid(dir, "120-prm-sections-unpaired", join(p), "bad_section", "3.4", "section 3 without section 4",
            kContainer);
  }
  invalid(dir, "121-unknown-section-id", with_crc(cat(cat(th, sec1), {0x10, 0x00})), "bad_section", "3.4",
          "section id 16", kContainer);
  // §3.3 Header fields.
  {
    Parts p = tp;
    p.bits = 21;
    invalid(dir, "122-header-position-bits", join(p), "bad_header", "3.3", "Position_Bits 21", kContainer);
    p = tp;
    p.step = 0;
    invalid(dir, "123-header-step", join(p), "bad_header", "3.3", "Step 0", kContainer);
    p = tp;
    p.origin[1] = std::nan("");
    invalid(dir, "124-header-origin", join(p), "bad_header", "3.3", "Origin_Y a NaN", kContainer);
    p = tp;
    p.bbox_min[2] = 1;
    invalid(dir, "125-header-bbox", join(p), "bad_header", "3.3", "Bbox_Min_Z 1 + Bbox_Extent_Z 4095 > 4095",
            kContainer);
    p = tp;
    p.vertices = 0;
    invalid(dir, "126-header-counts", join(p), "bad_header", "3.3", "Vertex_Count 0 with Triangle_Count 4",
            kContainer);
  }
  // §4.1 Caller limits (the runner passes the vector's limits).
  {
    DecodeLimits lim;
    lim.max_vertices = 3;
    invalid(dir, "127-limit-header", tetra, "count_exceeds_limit", "4.1",
            "the tetrahedron (4 vertices) for a caller allowing 3", kContainer, &lim);
    const std::vector<uint8_t> holes = general(sphere_with_holes(1, 2), 10);
    const Parts hp = split(holes);
    lim.max_vertices = hp.vertices;
    lim.max_triangles = hp.triangles;
    invalid(dir, "128-limit-closed-mesh", holes, "count_exceeds_limit", "4.1",
            "the mesh of 003 with limits equal to its header counts: its closed mesh (two dummy vertices) is larger",
            kS1, &lim);
  }
  // §4.3 Counts the stream cannot hold.
  {
    Parts p = tp;
    p.payload(1).pop_back();
    invalid(dir, "129-clers-shorter-than-4", join(p), "count_exceeds_stream", "4.2",
            "the tetrahedron's CLERS_Data cut to 3 bytes", kS1);
    p = tp;
    p.vertices = 10002;
    p.triangles = 20000;
    std::vector<uint8_t> c = {1};
    put_varint(c, 20000);
    p.payload(1) = cat(cat(c, {0, 0}), {0x7F, 0xFF, 0x80, 0x00});
    invalid(dir, "130-clers-too-many-symbols", join(p), "count_exceeds_stream", "4.2",
            "one component of 20000 triangles (19998 coded symbols) over 4 bytes of CLERS_Data (at most 2880)", kS1);
  }
  // §6 Connectivity.
  {
    Parts p = tp;
    p.vertices = 5;
    invalid(dir, "131-vertex-count", join(p), "bad_connectivity", "6.3",
            "Vertex_Count 5 for a closed mesh of 4 vertices", kS1);
    const std::vector<uint8_t> plate = general(plate_with_holes(1, 1), 12);
    p = split(plate);
    std::vector<uint8_t>& c = p.payload(1);
    size_t i = 0;
    const uint32_t k = get_varint(c, i);
    for (uint32_t n = 0; n < k; ++n) get_varint(c, i);
    const uint32_t handles = get_varint(c, i);
    if (handles == 0) std::exit(1);
    get_varint(c, i);  // Handle_Delta[0]
    c[i] |= 0x03;      // Handle_Partner[0]: Partner_Corner 3 (the low bits of its first byte)
    invalid(dir, "132-handle-partner-corner", join(p), "bad_connectivity", "6.3",
            "the mesh of 002 with Partner_Corner 3 in its first handle event", kS1);
    std::string what, cited;
    const std::vector<uint8_t> s = mutate(ico, 1, 4, "bad_connectivity", "6.4", "", what, &cited);
    invalid(dir, "133-clers-symbols", s, "bad_connectivity", cited.c_str(), what.c_str(), kS1);
    // A closed mesh without dummy vertices (so that §6.7's count cannot be met too) decoded with a triangle that
    // uses a vertex twice or two edges joining the same two vertices (§6.8).
    std::vector<uint8_t> n;
    for (const TestMesh& m : {torus(6, 6), icosphere(1), plate_with_holes(1, 1), torus(4, 8), icosphere(2)}) {
      n = mutate(general(m, 12), 1, 0, "non_manifold_result", "6.8", "", what, &cited, false);
      if (!n.empty()) break;
    }
    if (n.empty()) std::exit(1);
    invalid(dir, "134-non-manifold", n, "non_manifold_result", cited.c_str(), what.c_str(), kS1);
  }
  // §5.6 An initial Code of 0xFFFFFFFF, in each kind of block.
  {
    Parts p = tp;
    std::fill(p.payload(1).end() - 4, p.payload(1).end(), 0xFF);
    invalid(dir, "135-clers-initial-code", join(p), "bad_section", "5.6", "CLERS_Data FF FF FF FF", kS1);
    p = tp;
    std::fill(p.payload(2).begin(), p.payload(2).begin() + 4, 0xFF);
    invalid(dir, "136-positions-initial-code", join(p), "bad_section", "5.6", "the position block starts FF FF FF FF",
            kS2);
    p = split(prm);
    std::fill(p.payload(3).begin(), p.payload(3).begin() + 4, 0xFF);
    invalid(dir, "137-irregular-initial-code", join(p), "bad_section", "5.6",
            "the irregular-triangle block starts FF FF FF FF", kS3);
    p = split(prm);
    std::fill(p.payload(4).begin(), p.payload(4).begin() + 4, 0xFF);
    invalid(dir, "138-patches-initial-code", join(p), "bad_section", "5.6", "the patch block starts FF FF FF FF",
            kS4);
  }
  // §7.2, §8.4, §9.7 Fields of the PRM sections out of range, §8.3 and §9.7.4 bad positions, §10.4 a position
  // outside the box: a change inside the range-coded block, found by decoding (mutate()).
  {
    struct Case {
      const char* name;
      const std::vector<uint8_t>* stream;
      uint8_t id;
      const char* error;
      const char* sec;
      const char* has;
      const char* where;
    };
    const Case cases[] = {
        {"139-traversal-count", &prm, 3, "bad_section", "7.2", "count", kS3},
        {"140-traversal-start", &prm, 3, "bad_section", "7.2", "starts", kS3},
        {"141-grid-size", &prm, 4, "bad_section", "8.4", "Grid_Size", kS4},
        {"142-overlap-depth", &prm, 4, "bad_section", "9.7.2", "Overlap_Depth", kS4},
        {"143-predictor-weight", &prm, 4, "bad_section", "9.7.2", "weight", kS4},
        {"144-patch-axis", &prm, 4, "bad_section", "8.4", "axis or alignment", kS4},
        {"146-lattice-outside-box", &prm, 4, "bad_position", "8.3", "outside the bounding box", kS4},
        {"147-height-out-of-range", &prm, 4, "bad_position", "9.7.4", "height", kS4},
        {"148-position-outside-box", &ico, 2, "bad_position", "10.4", "outside", kS2},
    };
    // §8.3 A lattice conflict: section 3 of the pillow rewritten to hold no traversal (count 0, coded as §7.2
    // says), so that every triangle is regular and the first patch is the whole closed pillow, which no lattice
    // can hold: its propagation reaches some vertex twice, differently.
    {
      Parts p = split(prm);
      RangeEncoder rc;
      SignedIntModel count;
      encode_signed(rc, count, 0);
      p.payload(3) = rc.finish();
      invalid(dir, "145-lattice-conflict", join(p), "bad_position", "8.3",
              "the pillow's section 3 replaced by a block of no traversal: one patch of every triangle", kS4);
    }
    for (const Case& c : cases) {
      std::string what;
      const std::vector<uint8_t> s = mutate(*c.stream, c.id, 0, c.error, c.sec, c.has, what);
      invalid(dir, c.name, s, c.error, c.sec, what.c_str(), c.where);
    }
  }
  // §9.3 A height of a difference patch out of range, in the kept remeshed vector 019 (read from OUT_DIR).
  {
    std::ifstream f(dir / "vectors" / "019-prm-1.4-remeshed-rabbit-difference" / "stream.prm", std::ios::binary);
    const std::vector<uint8_t> rabbit((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (rabbit.empty()) {
      std::fprintf(stderr, "OUT_DIR/vectors/019-prm-1.4-remeshed-rabbit-difference/stream.prm is needed\n");
      std::exit(1);
    }
    std::string what;
    const std::vector<uint8_t> s = mutate(rabbit, 4, 0, "bad_position", "9.3", "height", what);
    invalid(dir, "149-difference-height-out-of-range", s, "bad_position", "9.3", what.c_str(), kS4);
  }
  // §3.4, §5.5 Reads past the end of a section's payload: a varint field, and a range-coded block.
  {
    Parts p = tp;
    p.payload(1) = {0x01, 0x84};
    invalid(dir, "154-truncated-connectivity-field", join(p), "truncated", "6.3",
            "section 1 is 01 84: Component_Count 1, then Component_Size cut", kS1);
    p = tp;
    p.payload(2).pop_back();
    invalid(dir, "155-truncated-positions-block", join(p), "truncated", "5.5",
            "the tetrahedron's position block without its last byte", kS2);
  }
  // §5.6 Bytes after the last decision of a block, in each kind of block.
  {
    const Parts pp = split(prm);
    const uint8_t ids[] = {1, 2, 3, 4};
    const char* names[] = {"150-trailing-clers", "151-trailing-positions", "152-trailing-irregular",
                           "153-trailing-patches"};
    const char* where[] = {kS1, kS2, kS3, kS4};
    for (int i = 0; i < 4; ++i) {
      Parts p = pp;
      p.payload(ids[i]).push_back(0x00);
      invalid(dir, names[i], join(p), "trailing_bytes", "5.6", "one byte 00 appended to the block", where[i]);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR [--only-prm-1.1 | --only-1.3 | --only-1.4 | --only-1.5 | --only-errors | --from-stream NAME FILE FORMAT FEATURE SECTIONS]\n", argv[0]);
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
  // A PRM stream made by the command line (`prm remesh` then `prm encode`, recorded in README.md), kept as a valid
  // vector with what it exercises.
  if (argc == 8 && std::string(argv[2]) == "--from-stream") {
    std::ifstream f(argv[4], std::ios::binary);
    const std::vector<uint8_t> stream((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    valid(dir, argv[3], stream, argv[5], argv[6], argv[7], prm_features(stream));
    return 0;
  }
  // Format 1.5 (§8.4.2 the grid table): a valid vector with two grid sizes, and the new field's range checks.
  if (argc > 2 && std::string(argv[2]) == "--only-1.5") {
    const std::vector<uint8_t> two = two_grid_stream(7);
    valid(dir, "020-prm-1.5-two-grids", two, "1.5",
          "PRM stream with the patch grids (Flags bit 4): a grid table of sizes 8 and 6, patches on each, bases from "
          "their references in their own lattices, linear prediction",
          "\"3.3\", \"8.4\", \"8.4.2\"", prm_features(two));
    const char* kS4 = "section 4 (patches)";
    const char* has[] = {"Extra_Grid_Count 0", "Extra_Grid out of range", "Grid_Index beyond the grid table"};
    const char* names[] = {"156-extra-grid-count", "157-extra-grid-size", "158-grid-index"};
    for (int k = 0; k < 3; ++k) {
      std::string what;
      const std::vector<uint8_t> bad = mutate(two, 4, 0, "bad_section", "8.4.2", has[k], what);
      invalid(dir, names[k], bad, "bad_section", "8.4.2", what.c_str(), kS4);
    }
    return 0;
  }
  if (argc > 2 && std::string(argv[2]) == "--only-errors") {
    error_vectors(dir);
    return 0;
  }
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
  error_vectors(dir);
  return 0;
}
