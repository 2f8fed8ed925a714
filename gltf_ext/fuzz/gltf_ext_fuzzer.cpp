// libFuzzer target: reading a glTF asset that carries PRM_mesh_compression (spec/PRM_mesh_compression/README.md), on
// arbitrary bytes, through the code `prm info` and `prm unpack` run on a .glb/.gltf (tools/prm/gltf_commands.cpp):
// print_gltf_prm_info (the document, every PRM primitive's extension object and stream decoded, the byte split),
// then run_gltf_unpack (every PRM, Draco and meshopt primitive decoded into accessors, the asset written).
//
// Input: a control byte, then the asset. Bit 0: the input is named .gltf (else .glb; read_document tells GLB from
// JSON by its magic either way); bit 1: the --json reports; bit 2: unpack writes a .gltf (else a .glb). The bytes
// go to a file in a private folder under /dev/shm (a .gltf's external buffers resolve there); stdout goes to
// /dev/null. Every input must end with both commands done or with prm::InputError / prm::IoError (the CLI's exit
// codes 2 and 4); any other exception (the CLI's "internal error", exit 3), a crash, a hang or memory beyond
// -rss_limit_mb is a finding.
//
// Build and run: codec/fuzz/run.sh [SECONDS] gltf_ext_fuzzer (codec/fuzz/README.md; seeds made by `prm pack`).
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gltf_commands.h"
#include "prm/error.h"

namespace {

std::string g_dir;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char tmpl[] = "/dev/shm/prm-gltf-ext-fuzz-XXXXXX";
  const char* d = mkdtemp(tmpl);
  if (!d) std::abort();
  g_dir = d;
  const int null = open("/dev/null", O_WRONLY);
  if (null < 0 || dup2(null, 1) < 0) std::abort();  // the reports of info/unpack; libFuzzer writes to stderr
  std::atexit([] {
    for (const char* f : {"input.glb", "input.gltf", "output.glb", "output.gltf"}) std::remove((g_dir + "/" + f).c_str());
    rmdir(g_dir.c_str());
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t control = data[0];
  const std::string in = g_dir + (control & 1 ? "/input.gltf" : "/input.glb");
  const std::string out = g_dir + (control & 4 ? "/output.gltf" : "/output.glb");
  std::FILE* f = std::fopen(in.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size > 1 && std::fwrite(data + 1, 1, size - 1, f) != size - 1) __builtin_trap();
  std::fclose(f);
  const bool json = control & 2;
  try {
    prm::cli::print_gltf_prm_info(in, json);
  } catch (const prm::InputError&) {
  } catch (const prm::IoError&) {
  }
  try {
    prm::cli::run_gltf_unpack(in, out, json);
  } catch (const prm::InputError&) {
  } catch (const prm::IoError&) {
  }
  std::fflush(stdout);
  return 0;
}
