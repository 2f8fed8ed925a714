#include "prm/pipeline/pack.h"

#include <chrono>

#include "prm/error.h"
#include "prm/mesh_validate.h"
#include "prm/metro_distance.h"
#include "prm/pipeline/codec_bridge.h"

namespace prm::pipeline {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

PackResult pack(const Mesh& input, const PackOptions& options) {
  PackResult out;
  auto t0 = std::chrono::steady_clock::now();
  // Paper §2: the remesher needs a closed manifold; the bunny's holes are closed by fans first.
  const MeshReport check = validate_mesh(input);
  Mesh closed;
  if (!check.closed() || !check.clean() || !check.manifold()) {
    closed = repair_mesh(input, &out.repair);  // throws InputError when it cannot be made a closed manifold
    out.repaired = true;
  }
  const Mesh& source = out.repaired ? closed : input;
  out.seconds_repair = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  remesh::RemeshOptions ro;
  ro.bits = options.bits;
  ro.reliefs.tau = options.tau;
  ro.reliefs.parallel = options.parallel;
  ro.parallel = options.parallel;
  ro.fit_heights = options.fit_heights;
  ro.grid_size = options.grid_size;
  ro.grid_fraction = options.grid_fraction;
  // The target bounds the decoded mesh: quantizing the PRM to the stream's bits adds about 2% to the RMS error
  // (12 bits, venus: 1.237e-4 -> 1.26e-4), so the search aims 4% below it.
  ro.target_error = kQuantizationMargin * options.target_error;
  MetroOptions mo;
  mo.samples = options.metro_samples;  // 0: Metro's ten per face, as `prm compare` measures
  const MetroReference reference(source, mo);
  auto error = [&](const Mesh& candidate) {
    const DistanceReport d = reference.compare(candidate);
    return remesh::ErrorEstimate{d.rel(d.rms), d.rel(d.max)};
  };
  out.remesh = remesh::remesh(source, ro, error);
  out.seconds_remesh = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  auto encoded = encode_prm_mesh(out.remesh.prm, &out.report);
  out.seconds_encode = seconds_since(t0);
  if (!encoded.ok())
    throw InputError("the piecewise regular mesh could not be encoded (a remesher or codec bug): " +
                     encoded.status.message + " (spec §" + encoded.status.spec_section + ")");
  out.stream = std::move(encoded.value);
  if (out.repaired) out.repaired_input = std::move(closed);
  return out;
}

}  // namespace prm::pipeline
