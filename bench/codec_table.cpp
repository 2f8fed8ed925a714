#include "codec_table.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

namespace prm::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Runs `call` `inner` times; returns the time per call, or a negative value if a call failed.
template <typename F>
double timed(F&& call, int inner) {
  const auto t0 = Clock::now();
  for (int k = 0; k < inner; ++k)
    if (!call()) return -1;
  return seconds_since(t0) / inner;
}

// How many calls make one round of at least `min_seconds`, from the time of one call.
int calls_per_round(double one_call, double min_seconds) {
  if (!(one_call > 0)) return 1000;
  return static_cast<int>(std::clamp(std::ceil(min_seconds / one_call), 1.0, 1e6));
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}
std::string sci(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3e", v);
  return buf;
}

}  // namespace

Row measure_row(const std::string& name, const Mesh& mesh, const std::vector<const Codec*>& codecs,
                const TableOptions& options) {
  Row row;
  row.mesh = name;
  row.vertices = mesh.num_vertices();
  row.faces = mesh.num_faces();
  row.results.resize(codecs.size());
  const double mv = static_cast<double>(mesh.num_vertices()) * 1e-6;

  // Round trip and error, codec by codec.
  std::vector<std::unique_ptr<CodecRun>> runs(codecs.size());
  std::vector<int> encode_calls(codecs.size(), 1), decode_calls(codecs.size(), 1);
  for (size_t c = 0; c < codecs.size(); ++c) {
    CodecResult& r = row.results[c];
    std::string why;
    try {
      runs[c] = codecs[c]->start(mesh, &why);
      if (!runs[c]) {
        r.failure = why.empty() ? "refused" : why;
        continue;
      }
      CodecRun& run = *runs[c];
      const double enc = timed([&] { return run.encode(); }, 1);
      if (enc < 0) {
        r.failure = run.failure();
        runs[c].reset();
        continue;
      }
      const double dec = timed([&] { return run.decode(); }, 1);
      if (dec < 0) {
        r.failure = run.failure();
        runs[c].reset();
        continue;
      }
      r.bytes = run.stream_bytes();
      r.bits_per_vertex = 8.0 * static_cast<double>(r.bytes) / static_cast<double>(mesh.num_vertices());
      const Mesh decoded = run.decoded_mesh();
      r.decoded_vertices = decoded.num_vertices();
      const DistanceReport d = metro_distance(mesh, decoded, options.metro);
      r.rms = d.rms;
      r.rms_rel = d.rel(d.rms);
      r.max_rel = d.rel(d.max);
      encode_calls[c] = calls_per_round(enc, options.min_round_seconds);
      decode_calls[c] = calls_per_round(dec, options.min_round_seconds);
      r.encode_seconds = r.decode_seconds = HUGE_VAL;
      r.ok = true;
    } catch (const std::exception& e) {
      r.failure = e.what();
      runs[c].reset();
    }
  }

  // Timing rounds, interleaved across codecs; the best round counts.
  for (int round = 0; round < options.rounds; ++round)
    for (size_t c = 0; c < codecs.size(); ++c) {
      if (!runs[c]) continue;
      CodecRun& run = *runs[c];
      CodecResult& r = row.results[c];
      const double enc = timed([&] { return run.encode(); }, encode_calls[c]);
      const double dec = timed([&] { return run.decode(); }, decode_calls[c]);
      if (enc > 0) r.encode_seconds = std::min(r.encode_seconds, enc);
      if (dec > 0) r.decode_seconds = std::min(r.decode_seconds, dec);
    }
  for (CodecResult& r : row.results)
    if (r.ok) {
      r.encode_mvps = mv / r.encode_seconds;
      r.decode_mvps = mv / r.decode_seconds;
    }
  return row;
}

void print_markdown(std::FILE* out, const std::vector<Row>& rows, const std::vector<const Codec*>& codecs) {
  std::fprintf(out, "| mesh | V | F |");
  for (const Codec* c : codecs) {
    const std::string n = c->name();
    std::fprintf(out, " %s bytes | bpv | RMS/diag | enc Mv/s | dec Mv/s |", n.c_str());
  }
  std::fprintf(out, "\n|---|---:|---:|");
  for (size_t c = 0; c < codecs.size(); ++c) std::fprintf(out, "---:|---:|---:|---:|---:|");
  std::fprintf(out, "\n");
  for (const Row& row : rows) {
    if (!row.failure.empty()) {
      std::fprintf(out, "| %s | | | not loaded: %s |\n", row.mesh.c_str(), row.failure.c_str());
      continue;
    }
    std::fprintf(out, "| %s | %zu | %zu |", row.mesh.c_str(), row.vertices, row.faces);
    for (const CodecResult& r : row.results) {
      if (!r.ok) {
        std::fprintf(out, " failed: %s | | | | |", r.failure.c_str());
        continue;
      }
      std::fprintf(out, " %zu | %s | %s | %s | %s |", r.bytes, fixed(r.bits_per_vertex, 3).c_str(),
                   sci(r.rms_rel).c_str(), fixed(r.encode_mvps, 2).c_str(), fixed(r.decode_mvps, 2).c_str());
    }
    std::fprintf(out, "\n");
  }
}

void print_csv(std::FILE* out, const std::vector<Row>& rows, const std::vector<const Codec*>& codecs) {
  std::fprintf(out, "mesh,vertices,faces");
  for (const Codec* c : codecs) {
    const std::string n = c->name();
    std::fprintf(out,
                 ",%s bytes,%s bits per vertex,%s rms,%s rms/diagonal,%s hausdorff/diagonal,%s decoded vertices,"
                 "%s encode s,%s decode s,%s encode Mv/s,%s decode Mv/s,%s failure",
                 n.c_str(), n.c_str(), n.c_str(), n.c_str(), n.c_str(), n.c_str(), n.c_str(), n.c_str(), n.c_str(),
                 n.c_str(), n.c_str());
  }
  std::fprintf(out, "\n");
  for (const Row& row : rows) {
    std::fprintf(out, "%s,%zu,%zu", row.mesh.c_str(), row.vertices, row.faces);
    for (size_t c = 0; c < codecs.size(); ++c) {
      if (c >= row.results.size() || !row.results[c].ok) {
        std::string why = !row.failure.empty() ? row.failure : row.results[c].failure;
        std::replace(why.begin(), why.end(), ',', ';');
        std::replace(why.begin(), why.end(), '\n', ' ');
        std::fprintf(out, ",,,,,,,,,,,%s", why.c_str());
        continue;
      }
      const CodecResult& r = row.results[c];
      std::fprintf(out, ",%zu,%.6f,%.9g,%.9g,%.9g,%zu,%.9g,%.9g,%.6f,%.6f,", r.bytes, r.bits_per_vertex, r.rms,
                   r.rms_rel, r.max_rel, r.decoded_vertices, r.encode_seconds, r.decode_seconds, r.encode_mvps,
                   r.decode_mvps);
    }
    std::fprintf(out, "\n");
  }
}

}  // namespace prm::bench
