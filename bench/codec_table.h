// The codec comparison table of bench/README.md: one row per mesh, one column group per codec configuration
// (stream bytes, bits per vertex, RMS error of the decoded mesh, encode and decode speed).
//
// A codec joins the table by implementing Codec (a name and a way to start a run on a mesh) and CodecRun (encode,
// decode, give the decoded mesh back); draco_codec.h is the example. The driver (measure_row) does the rest the same
// way for every codec: one checked round trip, the Metro error of the decoded mesh, then interleaved timing rounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "prm/mesh.h"
#include "prm/metro_distance.h"

namespace prm::bench {

// One codec on one mesh. The constructor (Codec::start) does the untimed preparation, e.g. converting prm::Mesh to
// the codec's own mesh type; encode() and decode() are what gets timed, so they should do exactly the codec's work.
class CodecRun {
 public:
  virtual ~CodecRun() = default;
  // Encodes the prepared input; keeps the stream. Returns false (and sets failure()) if the codec refuses.
  virtual bool encode() = 0;
  virtual size_t stream_bytes() const = 0;
  // Decodes the kept stream; keeps the result. Returns false (and sets failure()) on error.
  virtual bool decode() = 0;
  // The last decoded mesh as a prm::Mesh (untimed), for the error measurement.
  virtual Mesh decoded_mesh() const = 0;
  const std::string& failure() const { return failure_; }

 protected:
  std::string failure_;
};

// A codec configuration: one column group of the table.
class Codec {
 public:
  virtual ~Codec() = default;
  virtual std::string name() const = 0;  // the column group's title, e.g. "Draco L10"
  // Prepares a run on `mesh` (which outlives the run). May return nullptr with a reason in *why.
  virtual std::unique_ptr<CodecRun> start(const Mesh& mesh, std::string* why) const = 0;
};

struct TableOptions {
  int rounds = 7;                  // timing rounds; the best (fastest) round of each codec is kept
  double min_round_seconds = 0.1;  // each round repeats the call until it has run this long
  MetroOptions metro;              // sampling of the error measurement (default: Metro's, ten per face)
};

struct CodecResult {
  bool ok = false;
  std::string failure;          // why there is no result
  size_t bytes = 0;             // stream size
  size_t decoded_vertices = 0;  // may differ from the input (a codec may split or merge vertices)
  double bits_per_vertex = 0;   // 8 · bytes / input vertices
  double rms = 0;               // symmetric Metro RMS distance, decoded vs original (absolute)
  double rms_rel = 0;           // the same as a fraction of the original's bounding-box diagonal
  double max_rel = 0;           // symmetric Hausdorff distance / diagonal
  double encode_seconds = 0;    // best per-call time
  double decode_seconds = 0;
  double encode_mvps = 0;       // input vertices / encode time, millions per second
  double decode_mvps = 0;
};

struct Row {
  std::string mesh;  // display name
  size_t vertices = 0, faces = 0;
  std::string failure;  // the mesh itself could not be loaded
  std::vector<CodecResult> results;  // one per codec, in table order
};

// Measures every codec on one mesh: round trip, error, then `rounds` timing rounds interleaved across codecs
// (encode A, decode A, encode B, decode B, ...), so that a drifting machine affects all columns alike.
Row measure_row(const std::string& name, const Mesh& mesh, const std::vector<const Codec*>& codecs,
                const TableOptions& options);

void print_markdown(std::FILE* out, const std::vector<Row>& rows, const std::vector<const Codec*>& codecs);
void print_csv(std::FILE* out, const std::vector<Row>& rows, const std::vector<const Codec*>& codecs);

}  // namespace prm::bench
