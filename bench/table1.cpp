// prm_bench_table1: the paper's Table 1, reproduced (bench/README.md, "Table 1"). For every mesh of
// ../shared/meshes and the dense closed meshes of CGAL's data set: repair (holes, pinches), remesh to a target RMS
// error (the paper's e for its models, 2e-4 of the diagonal otherwise), encode as a PRM stream, decode, and measure
//   n_o, n_r, g          input vertices, PRM vertices, grid size (model units and fraction of the diagonal)
//   e                    symmetric Metro RMS distance of the DECODED PRM to the original (to the repaired original
//                        when it had holes), fraction of the diagonal; pack() aims the remesh at 0.96 x the target
//   S_o, S_r             Draco 1.5.5 (edgebreaker, 12 bits, level 10) on the original and on the PRM, kilobytes
//   conn, irreg, geom    the PRM stream's byte split (connectivity, irregular triangles, geometry), kilobytes
//   total, bpv           the whole PRM stream (container included), kilobytes and bits per PRM vertex
//   enc, dec, remesh     PRM encode time, PRM decode time, remesh time (grid search included); and Draco's decode
//                        time on the original and on the same PRM (S_r's stream: the mesh our stream decodes to, at
//                        its bits on its grid) in the same run (interleaved rounds, best round kept; encode and decode
//                        times are the calling thread's CPU time, which the other jobs of a shared machine distort
//                        far less than wall time); decode speed per PRM vertex against Draco's on the same PRM
// followed by the paper's own rows (its Table 1). Kilobytes are 1024 bytes, as the paper's (a 12-bit venus at
// 116.3 KB). The stream's bit depth is pack()'s choice (the smallest stream meeting the target; "bits"); each paper
// model gets two more rows: "(12 bits)", the paper's protocol, and "(12 bits, paper n_r)", remeshed at the grid that
// gives about the paper's vertex count (its e is then below the paper's), so that bits per vertex compare at equal
// sampling density. S_r is Draco at the stream's bit depth, S_o Draco at 12 bits.
// mode: the stream pack()'s default mode (auto, issue 22) kept, prm or general (the input coded as it is, at the
// smallest bit depth meeting the target), with the other candidate's size; a general row's g and regular are 0,
// its n_r is n_o, its "S_r" columns are Draco on the decoded input, its enc the general path at its bit depth and
// its remesh the time of the PRM candidate it did not keep.
//
//   prm_bench_table1 [--csv=FILE] [--meshes=SUB[,SUB...]] [--target=E] [--rounds=N] [--no-cgal] [--no-paper-density]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cpu_time.h"
#include "draco_codec.h"
#include "prm/codec.h"
#include "prm/mesh_io.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"
#include "prm/pipeline/pack.h"

namespace {

// The paper's Table 1 (Szymczak, Rossignac, King): n_o, n_r, g, e·1e4, S_o, S_r, conn, irreg, geom, total (KB),
// decode time (s, 650 MHz Pentium III).
struct PaperRow {
  const char* model;
  const char* here;  // our file of the same model ("" when we do not have it)
  double n_o, n_r, g, e4, s_o, s_r, conn, irreg, geom, total, t;
};
const PaperRow kPaper[] = {
    {"Venus", "venus.off", 50002, 45428, 0.007, 1.3, 116.3, 43.1, 1.7, 0.7, 19.0, 21.4, 0.73},
    {"horse", "horse.ply", 48485, 34401, 0.001, 1.3, 73.3, 35.8, 2.1, 1.0, 12.6, 15.8, 0.54},
    {"rabbit", "", 67038, 21183, 0.0005, 1.1, 100.0, 23.0, 1.2, 0.6, 9.1, 10.8, 0.32},
    {"feline", "feline.off", 49864, 38431, 0.008, 2.6, 88.4, 40.4, 3.0, 1.7, 17.9, 22.6, 0.65},
    {"bunny", "bunny_zipper.ply", 34839, 24499, 0.0015, 2.0, 49.1, 24.2, 1.3, 0.6, 12.4, 14.4, 0.38},
};

// CGAL's data/meshes: the dense, closed, manifold ones (as in the Draco baseline).
const char* const kCgalMeshes[] = {"bunny00.off", "refined_elephant.off", "armadillo.off", "diplodocus.off",
                                   "man.off",     "bear.off",             "camel.off",     "turbine.off",
                                   "bull.off",    "homer.off",            "cow.off",       "elephant.off"};

struct Result {
  std::string mesh;
  std::string failure;
  double target = 0;
  size_t n_o = 0, n_r = 0;
  double g = 0, g_rel = 0, e = 0, e_max = 0;
  double regular_share = 0;
  size_t s_o = 0, s_r = 0;  // Draco bytes (S_r at the stream's bit depth)
  size_t s_r12 = 0;          // Draco on the PRM at 12 bits, the paper's protocol
  size_t s_re = 0;           // Draco on the PRM at the fewest bits (bits_re) whose decoded mesh meets the target
  int bits_re = 0;           // 0: none up to 16 bits
  double e_r = 0;            // the error of Draco's decoded PRM at the stream's bit depth
  size_t conn = 0, irreg = 0, geom = 0, total = 0;
  double enc = 0, dec = 0, draco_dec = 0, remesh = 0;
  double draco_dec_same = 0;  // Draco decoding S_r's stream (the same PRM, the stream's bits and grid)
  int bits = 12;  // the stream's quantization; Draco's S_r uses the same (S_o: 12 bits)
  double step_scale = 1;  // the stream's step in units of 2^-bits of the extent (PackResult::step_scale)
  std::string mode = "prm";  // PackResult::mode (auto chose it)
  size_t other_bytes = 0;    // the candidate auto did not keep (0: not made)
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

double paper_target(const std::string& file, double fallback) {
  for (const PaperRow& p : kPaper)
    if (file == p.here) return p.e4 * 1e-4;
  return fallback;
}

// grid_size > 0: remesh at that grid size (model units) instead of searching the one for `target`. bits: the
// stream's quantization (0: pack() chooses, the smallest stream that meets the target).
Result measure(const std::string& name, const std::string& path, double target, int rounds, double grid_size = 0,
               int bits = 0) {
  Result r;
  r.mesh = name;
  r.target = target;
  const prm::Mesh original = prm::read_mesh(path);
  r.n_o = original.num_vertices();

  prm::pipeline::PackOptions po;
  po.bits = bits;
  po.effort = prm::pipeline::kMaxEffort;  // the paper comparison: the smallest stream the exhaustive search finds
  po.fill_holes = true;  // the paper's protocol: holes closed by fans (paper §4; pack keeps them open by default)
  if (grid_size > 0)
    po.grid_size = grid_size;
  else
    po.target_error = target;  // pack() aims 4% below it, for the stream's quantization
  const prm::pipeline::PackResult pack = prm::pipeline::pack(original, po);
  r.remesh = pack.seconds_repair + pack.seconds_remesh;
  r.bits = pack.bits;
  r.step_scale = pack.step_scale;
  const bool general = pack.mode == prm::pipeline::PackMode::general;
  r.mode = prm::pipeline::pack_mode_name(pack.mode);
  const auto& other = general ? pack.prm_candidate : pack.general_candidate;
  r.other_bytes = other.made ? other.bytes : 0;
  r.n_r = pack.report.vertices;
  r.g = general ? 0 : static_cast<double>(pack.remesh.prm.lattice.A) * pack.remesh.prm.frame.step;
  r.g_rel = r.g / prm::bbox_diagonal(original);
  r.regular_share = pack.remesh.prm.stats.faces
                        ? static_cast<double>(pack.remesh.prm.stats.regular_faces) / pack.remesh.prm.stats.faces
                        : 0;
  r.total = pack.stream.size();
  r.conn = pack.report.connectivity_bytes;
  r.irreg = pack.report.irregular_bytes;
  r.geom = pack.report.total_bytes - pack.report.connectivity_bytes - pack.report.irregular_bytes -
           pack.report.header_bytes - pack.report.framing_bytes;

  // Encode time: the codec alone (the pack timed the PRM's once; take the best of a few more). A general stream: the
  // input through the general path at the stream's bit depth (pack timed its whole bit-depth search, not one encode).
  const double encode_best = prm::bench::best_cpu_time(
      [&] {
        prm::codec::EncodeReport rep;
        if (general)
          (void)prm::pipeline::encode_any_mesh(original, pack.bits, &rep);
        else
          (void)prm::pipeline::encode_prm_mesh(pack.remesh.prm, &rep);
      },
      std::max(1, rounds / 3));
  r.enc = general ? encode_best : std::min(pack.seconds_encode, encode_best);

  // Decode, and the error of the decoded PRM against the original.
  const auto decoded = prm::codec::decode(pack.stream.data(), pack.stream.size());
  if (!decoded.ok()) throw std::runtime_error("decode failed: " + decoded.status.message);
  const prm::Mesh out = prm::pipeline::to_mesh(decoded.value);
  // A mesh with holes is measured against its repaired version (holes closed by fans, paper §4): what was
  // remeshed. Draco's S_o is still the original's.
  const prm::DistanceReport d = prm::metro_distance(pack.repaired ? pack.repaired_input : original, out);
  r.e = d.rel(d.rms);
  r.e_max = d.rel(d.max);

  // Draco on the original and on the PRM mesh.
  // At the stream's bit depth Draco gets the stream's own grid (origin and step; with a step scale above 1 its
  // bounding-box grid would not hold our positions); at 12 bits and elsewhere, Draco's default.
  prm::bench::DracoGrid grid;
  for (int a = 0; a < 3; ++a) grid.origin[static_cast<size_t>(a)] = static_cast<float>(decoded.value.frame.origin[static_cast<size_t>(a)]);
  grid.range = static_cast<float>(decoded.value.frame.step * static_cast<double>((1 << pack.bits) - 1));
  const prm::bench::DracoCodec draco(10), draco_same_bits(10, pack.bits, grid);
  std::string why;
  auto on_original = draco.start(original, &why);
  if (!on_original || !on_original->encode()) throw std::runtime_error("Draco on the original: " + why);
  r.s_o = on_original->stream_bytes();
  // "The same PRM": the mesh the stream holds (the decoded one; its heights are the encoder's choice).
  auto on_prm = draco_same_bits.start(out, &why);
  if (!on_prm || !on_prm->encode()) throw std::runtime_error("Draco on the PRM: " + why);
  r.s_r = on_prm->stream_bytes();
  auto on_prm12 = draco.start(out, &why);
  if (!on_prm12 || !on_prm12->encode()) throw std::runtime_error("Draco on the PRM at 12 bits: " + why);
  r.s_r12 = on_prm12->stream_bytes();
  // Equal error: Draco on the same PRM at the fewest bits whose decoded mesh meets the target too (its quantization
  // adds to the PRM's error: at the stream's bit depth it often misses the target our stream meets). From one bit
  // below the stream's: with a step scale above 1 our step lies between those of two Draco bit depths.
  const prm::Mesh& reference = pack.repaired ? pack.repaired_input : original;
  for (int b = std::max(8, pack.bits - 1); b <= 16 && (r.bits_re == 0 || b <= pack.bits); ++b) {
    // At the stream's bit depth, S_r's run (encoded above) is decoded; the other depths are Draco's default grid.
    std::unique_ptr<prm::bench::CodecRun> other;
    prm::bench::CodecRun* run = on_prm.get();
    if (b != pack.bits) {
      other = prm::bench::DracoCodec(10, b).start(out, &why);
      run = other.get();
      if (!run || !run->encode()) throw std::runtime_error("Draco on the PRM at " + std::to_string(b) + " bits: " + why);
    }
    if (!run->decode()) throw std::runtime_error("Draco on the PRM at " + std::to_string(b) + " bits: " + why);
    const prm::DistanceReport dd = prm::metro_distance(reference, run->decoded_mesh());
    if (b == pack.bits) r.e_r = dd.rel(dd.rms);
    if (dd.rel(dd.rms) <= target && r.bits_re == 0) {
      r.bits_re = b;
      r.s_re = run->stream_bytes();
    }
  }

  // Decode times, interleaved: PRM's stream, Draco's stream of the original, Draco's stream of the same PRM.
  r.dec = r.draco_dec = r.draco_dec_same = HUGE_VAL;
  for (int k = 0; k < rounds; ++k) {
    r.dec = std::min(r.dec, prm::bench::best_cpu_time([&] { (void)prm::codec::decode(pack.stream.data(), pack.stream.size()); }, 2));
    r.draco_dec = std::min(r.draco_dec, prm::bench::best_cpu_time([&] { (void)on_original->decode(); }, 2));
    r.draco_dec_same = std::min(r.draco_dec_same, prm::bench::best_cpu_time([&] { (void)on_prm->decode(); }, 2));
  }
  return r;
}

std::string kb(size_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", static_cast<double>(bytes) / 1024.0);
  return buf;
}

std::string ratio_or_dash(size_t a, size_t b) {
  if (b == 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", static_cast<double>(a) / static_cast<double>(b));
  return buf;
}

void print_markdown(const std::vector<Result>& rows) {
  std::printf(
      "| mesh | n_o | n_r | g | g/diag | bits | mode (other) | regular | e·1e4 | max·1e4 | S_o KB | S_r KB | conn KB | irreg KB | geom KB | "
      "total KB | bpv | total/S_o | total/S_r | total/S_r12 | Draco e·1e4 at bits | S_r(e) bits | total/S_r(e) | "
      "enc ms | dec ms | Draco dec ms | dec Draco/PRM | dec ns/vertex | Draco same PRM ns/vertex | vertices/s PRM/Draco "
      "same PRM | remesh s |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Result& r : rows) {
    if (!r.failure.empty()) {
      std::printf("| %s | %zu | %s ||||||||||||||||||||||||||\n", r.mesh.c_str(), r.n_o, r.failure.c_str());
      continue;
    }
    char bits[32];
    if (r.step_scale != 1)
      std::snprintf(bits, sizeof bits, "%d ×%.2f", r.bits, r.step_scale);
    else
      std::snprintf(bits, sizeof bits, "%d", r.bits);
    char mode[64];
    if (r.other_bytes)
      std::snprintf(mode, sizeof mode, "%s (%s %s KB)", r.mode.c_str(), r.mode == "prm" ? "general" : "prm",
                    kb(r.other_bytes).c_str());
    else
      std::snprintf(mode, sizeof mode, "%s", r.mode.c_str());
    std::printf("| %s | %zu | %zu | %.4g | %.5f | %s | %s | %.1f%% | %.2f | %.2f | %s | %s | %s | %s | %s | **%s** | **%.2f** | %.3f | "
                "%.3f | %.3f | %.2f | %d | %s | %.1f | %.1f | %.1f | %.2f | %.0f | %.0f | %.2f | %.1f |\n",
                r.mesh.c_str(), r.n_o, r.n_r, r.g, r.g_rel, bits, mode, 100 * r.regular_share, r.e * 1e4, r.e_max * 1e4, kb(r.s_o).c_str(),
                kb(r.s_r).c_str(), kb(r.conn).c_str(), kb(r.irreg).c_str(), kb(r.geom).c_str(), kb(r.total).c_str(),
                8.0 * static_cast<double>(r.total) / static_cast<double>(r.n_r),
                static_cast<double>(r.total) / static_cast<double>(r.s_o),
                static_cast<double>(r.total) / static_cast<double>(r.s_r),
                static_cast<double>(r.total) / static_cast<double>(r.s_r12), r.e_r * 1e4, r.bits_re,
                ratio_or_dash(r.total, r.s_re).c_str(),
                1e3 * r.enc, 1e3 * r.dec,
                1e3 * r.draco_dec, r.draco_dec / r.dec, 1e9 * r.dec / static_cast<double>(r.n_r),
                1e9 * r.draco_dec_same / static_cast<double>(r.n_r), r.draco_dec_same / r.dec, r.remesh);
  }
  std::printf("\nThe paper's Table 1 (its models; KB; T = decode seconds on a 650 MHz Pentium III):\n\n");
  std::printf("| model | n_o | n_r | g | e·1e4 | S_o KB | S_r KB | conn KB | irreg KB | geom KB | total KB | bpv | "
              "total/S_o | total/S_r | T s |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const PaperRow& p : kPaper)
    std::printf("| %s | %.0f | %.0f | %g | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.3f | %.3f | %.2f |\n",
                p.model, p.n_o, p.n_r, p.g, p.e4, p.s_o, p.s_r, p.conn, p.irreg, p.geom, p.total,
                8192.0 * p.total / p.n_r, p.total / p.s_o, p.total / p.s_r, p.t);
}

void print_csv(std::FILE* f, const std::vector<Result>& rows) {
  std::fprintf(f,
               "source,mesh,target,n_o,n_r,g,g_rel,bits,step_scale,mode,other_bytes,regular_share,e,e_max,s_o_bytes,s_r_bytes,s_r12_bytes,draco_prm_e,"
               "s_re_bits,s_re_bytes,conn_bytes,irreg_bytes,"
               "geom_bytes,total_bytes,bpv,total_over_s_o,total_over_s_r,encode_s,decode_s,draco_decode_s,draco_same_prm_decode_s,remesh_s,"
               "failure\n");
  for (const Result& r : rows)
    std::fprintf(f, "ours,\"%s\",%g,%zu,%zu,%.9g,%.9g,%d,%.6g,%s,%zu,%.6f,%.6g,%.6g,%zu,%zu,%zu,%.6g,%d,%zu,%zu,%zu,%zu,%zu,%.4f,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%.4g,%s\n",
                 r.mesh.c_str(), r.target, r.n_o, r.n_r, r.g, r.g_rel, r.bits, r.step_scale, r.mode.c_str(), r.other_bytes, r.regular_share, r.e, r.e_max, r.s_o, r.s_r,
                 r.s_r12, r.e_r, r.bits_re, r.s_re,
                 r.conn, r.irreg, r.geom, r.total, r.n_r ? 8.0 * static_cast<double>(r.total) / static_cast<double>(r.n_r) : 0.0,
                 r.s_o ? static_cast<double>(r.total) / static_cast<double>(r.s_o) : 0.0,
                 r.s_r ? static_cast<double>(r.total) / static_cast<double>(r.s_r) : 0.0, r.enc, r.dec, r.draco_dec,
                 r.draco_dec_same, r.remesh, r.failure.c_str());
  for (const PaperRow& p : kPaper)
    std::fprintf(f, "paper,\"%s\",%g,%.0f,%.0f,%g,,12,1,prm,,,%g,,%.0f,%.0f,,,,,%.0f,%.0f,%.0f,%.0f,%.4f,%.4f,%.4f,,%g,,,,\n", p.model,
                 p.e4 * 1e-4, p.n_o, p.n_r, p.g, p.e4 * 1e-4, p.s_o * 1024, p.s_r * 1024, p.conn * 1024,
                 p.irreg * 1024, p.geom * 1024, p.total * 1024, 8192.0 * p.total / p.n_r, p.total / p.s_o,
                 p.total / p.s_r, p.t);
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s [--csv=FILE] [--meshes=SUB[,SUB...]] [--target=E] [--rounds=N] [--no-cgal] "
               "[--no-paper-density]\n",
               argv0);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv_file;
  std::vector<std::string> filters;
  double target = 2e-4;
  int rounds = 5;
  bool cgal = true, paper_density = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* key) -> const char* {
      const std::string k = std::string(key) + "=";
      return a.compare(0, k.size(), k) == 0 ? argv[i] + k.size() : nullptr;
    };
    if (a == "--help" || a == "-h") {
      usage(argv[0]);
      return 0;
    } else if (const char* v = value("--csv")) {
      csv_file = v;
    } else if (const char* v = value("--meshes")) {
      filters = split(v, ',');
    } else if (const char* v = value("--target")) {
      target = std::atof(v);
    } else if (const char* v = value("--rounds")) {
      rounds = std::max(1, std::atoi(v));
    } else if (a == "--no-cgal") {
      cgal = false;
    } else if (a == "--no-paper-density") {
      paper_density = false;
    } else {
      return usage(argv[0]);
    }
  }
  if (!(target > 0 && target < 0.1)) return usage(argv[0]);

  struct Entry {
    std::string name, path;
  };
  std::vector<Entry> entries;
  std::vector<std::string> shared;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(PRM_SHARED_MESHES, ec)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".ply" || ext == ".off" || ext == ".obj"))
      shared.push_back(e.path().filename().string());
  }
  std::sort(shared.begin(), shared.end());
  for (const std::string& f : shared) entries.push_back({f, std::string(PRM_SHARED_MESHES) + "/" + f});
  if (cgal)
    for (const char* f : kCgalMeshes) entries.push_back({std::string("cgal/") + f, std::string(PRM_CGAL_MESHES) + "/" + f});

  std::vector<Result> rows;
  for (const Entry& e : entries) {
    if (!filters.empty() && std::none_of(filters.begin(), filters.end(),
                                         [&](const std::string& f) { return e.name.find(f) != std::string::npos; }))
      continue;
    const double t = paper_target(e.name, target);
    std::fprintf(stderr, "table1: %s (target e %.2g)\n", e.name.c_str(), t);
    try {
      rows.push_back(measure(e.name, e.path, t, rounds));
      // The paper's models also by the paper's protocol, 12 bits; and once more at 12 bits and the paper's vertex
      // count: the grid scaled by sqrt(n_r / paper's n_r) (the vertex density goes as 1 / g^2), so that bits per
      // vertex compare at equal sampling.
      for (const PaperRow& p : kPaper)
        if (paper_density && e.name == p.here && rows.back().failure.empty()) {
          std::fprintf(stderr, "table1: %s at 12 bits\n", e.name.c_str());
          rows.push_back(measure(e.name + " (12 bits)", e.path, t, rounds, 0, 12));
          const double g = rows.back().g * std::sqrt(static_cast<double>(rows.back().n_r) / p.n_r);
          std::fprintf(stderr, "table1: %s at the paper's n_r %.0f (grid %.4g)\n", e.name.c_str(), p.n_r, g);
          rows.push_back(measure(e.name + " (12 bits, paper n_r)", e.path, t, rounds, g, 12));
        }
    } catch (const std::exception& ex) {
      Result r;
      r.mesh = e.name;
      r.target = t;
      r.failure = ex.what();
      rows.push_back(r);
    }
  }
  print_markdown(rows);
  if (!csv_file.empty()) {
    std::FILE* f = std::fopen(csv_file.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "table1: cannot write %s\n", csv_file.c_str());
      return 4;
    }
    print_csv(f, rows);
    std::fclose(f);
  }
  return 0;
}
