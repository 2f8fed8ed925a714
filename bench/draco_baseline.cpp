// prm_bench_draco_baseline: the Draco baseline table (issue 2; bench/README.md). Every mesh of ../shared/meshes and
// the sizeable closed manifold meshes of CGAL's data set, encoded and decoded by Draco 1.5.5 (edgebreaker, positions
// only, 12-bit quantization) at compression levels 7 and 10: stream bytes, bits per vertex, symmetric Metro RMS error
// of the decoded mesh as a fraction of the original's bounding-box diagonal, encode and decode speed in millions of
// input vertices per second (best of several interleaved rounds of repeated calls: codec_table.h).
//
// Another codec joins the table as one more Codec in `codecs` below (see draco_codec.h for the pattern).
//
//   prm_bench_draco_baseline [--csv | --csv=FILE] [--meshes=SUB[,SUB...]] [--levels=7,10] [--rounds=7]
//                            [--min-round=0.1] [--samples=N] [--seed=S]
//     --csv        CSV instead of the Markdown table on stdout (more columns: absolute RMS, Hausdorff, times)
//     --csv=FILE   the Markdown table on stdout and the CSV in FILE
//     --meshes     only meshes whose name contains one of the substrings
//     --samples    Metro samples per surface for the error (default: ten per face, Metro's default)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "codec_table.h"
#include "draco_codec.h"
#include "prm/mesh_io.h"

namespace {

// CGAL's data/meshes: the dense, closed, manifold ones (checked with `prm info`), largest first.
const char* const kCgalMeshes[] = {"bunny00.off", "refined_elephant.off", "armadillo.off", "diplodocus.off",
                                   "man.off",     "fandisk_large.off",    "bear.off",      "bear_bis.off",
                                   "camel.off",   "turbine.off",          "cheese.off",    "bull.off",
                                   "homer.off",   "cow.off",              "elephant.off"};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

bool has_mesh_extension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

struct Entry {
  std::string name, path;
};

std::vector<Entry> mesh_list() {
  std::vector<Entry> out;
  std::vector<std::string> shared;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(PRM_SHARED_MESHES, ec))
    if (e.is_regular_file() && has_mesh_extension(e.path())) shared.push_back(e.path().filename().string());
  if (ec) std::fprintf(stderr, "draco_baseline: cannot list %s: %s\n", PRM_SHARED_MESHES, ec.message().c_str());
  std::sort(shared.begin(), shared.end());
  for (const std::string& f : shared) out.push_back({f, std::string(PRM_SHARED_MESHES) + "/" + f});
  for (const char* f : kCgalMeshes) out.push_back({std::string("cgal/") + f, std::string(PRM_CGAL_MESHES) + "/" + f});
  return out;
}

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s [--csv | --csv=FILE] [--meshes=SUB[,SUB...]] [--levels=7,10] [--rounds=N]\n"
               "          [--min-round=SECONDS]"
               " [--samples=N] [--seed=S]\n",
               argv0);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  bool csv = false;
  std::string csv_file;
  std::vector<std::string> filters;
  std::vector<int> levels = {7, 10};
  prm::bench::TableOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* key) -> const char* {
      const std::string k = std::string(key) + "=";
      return a.compare(0, k.size(), k) == 0 ? argv[i] + k.size() : nullptr;
    };
    if (a == "--help" || a == "-h") {
      usage(argv[0]);
      return 0;
    } else if (a == "--csv") {
      csv = true;
    } else if (const char* v = value("--csv")) {
      csv_file = v;
    } else if (const char* v = value("--meshes")) {
      filters = split(v, ',');
    } else if (const char* v = value("--levels")) {
      levels.clear();
      for (const std::string& l : split(v, ',')) levels.push_back(std::atoi(l.c_str()));
    } else if (const char* v = value("--rounds")) {
      options.rounds = std::max(1, std::atoi(v));
    } else if (const char* v = value("--min-round")) {
      options.min_round_seconds = std::atof(v);
    } else if (const char* v = value("--samples")) {
      options.metro.samples = std::strtoull(v, nullptr, 10);
    } else if (const char* v = value("--seed")) {
      options.metro.seed = std::strtoull(v, nullptr, 10);
    } else {
      return usage(argv[0]);
    }
  }
  for (int l : levels)
    if (l < 0 || l > 10) return usage(argv[0]);

  std::vector<std::unique_ptr<prm::bench::Codec>> owned;
  for (int l : levels) owned.push_back(std::make_unique<prm::bench::DracoCodec>(l));
  std::vector<const prm::bench::Codec*> codecs;
  for (const auto& c : owned) codecs.push_back(c.get());

  std::vector<prm::bench::Row> rows;
  for (const Entry& e : mesh_list()) {
    if (!filters.empty() && std::none_of(filters.begin(), filters.end(),
                                         [&](const std::string& f) { return e.name.find(f) != std::string::npos; }))
      continue;
    std::fprintf(stderr, "draco_baseline: %s\n", e.name.c_str());
    try {
      const prm::Mesh mesh = prm::read_mesh(e.path);
      rows.push_back(prm::bench::measure_row(e.name, mesh, codecs, options));
    } catch (const std::exception& ex) {
      prm::bench::Row row;
      row.mesh = e.name;
      row.failure = ex.what();
      rows.push_back(row);
    }
  }
  if (csv)
    prm::bench::print_csv(stdout, rows, codecs);
  else
    prm::bench::print_markdown(stdout, rows, codecs);
  if (!csv_file.empty()) {
    std::FILE* f = std::fopen(csv_file.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "draco_baseline: cannot write %s\n", csv_file.c_str());
      return 4;
    }
    prm::bench::print_csv(f, rows, codecs);
    std::fclose(f);
  }
  return 0;
}
