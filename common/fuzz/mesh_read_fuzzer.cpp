// libFuzzer target: the mesh readers (common/src/mesh_io_*.cpp) on arbitrary bytes, through prm::read_mesh, the
// entry `prm pack/encode/compare/info` use.
//
// Input: a control byte, then the file. The control byte's low three bits choose the format the bytes are read as
// (0 PLY, 1 OBJ, 2 OFF, 3 STL, 4 glTF text, 5 GLB, 6 and 7: no format given, the file named .bin so read_mesh sniffs
// it from the content); bit 3 welds every format within a tolerance (Weld::Always, 1e-3), bit 4 drops PLY's extra
// properties. PLY ASCII and binary are the same reader, chosen by the header (the seeds hold both).
// The bytes are written to a file in a private folder under /dev/shm (read_mesh reads files; a .gltf's external
// buffers resolve there). Every input must end in a mesh or prm::InputError / prm::IoError (the CLI's exit codes 2
// and 4); any other exception is a finding (the CLI would call it an internal error, exit 3), and so are a crash, a
// hang (-timeout) or memory beyond -rss_limit_mb: nothing may be allocated for a count before the bytes it needs are
// seen to exist. A mesh read must have its indices in range and finite positions.
//
// Build and run: codec/fuzz/run.sh [SECONDS] mesh_read_fuzzer (codec/fuzz/README.md; seeds from ../shared/meshes).
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "prm/error.h"
#include "prm/mesh_io.h"

namespace {

std::string g_dir;

std::string write_input(const uint8_t* data, size_t size, const char* ext) {
  const std::string path = g_dir + "/input." + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) __builtin_trap();
  if (size && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char tmpl[] = "/dev/shm/prm-mesh-read-fuzz-XXXXXX";
  const char* d = mkdtemp(tmpl);
  if (!d) {
    char alt[] = "/tmp/prm-mesh-read-fuzz-XXXXXX";
    d = mkdtemp(alt);
    if (!d) std::abort();
    g_dir = d;
  } else {
    g_dir = d;
  }
  std::atexit([] {
    for (const char* e : {"ply", "obj", "off", "stl", "gltf", "glb", "bin"}) std::remove((g_dir + "/input." + e).c_str());
    rmdir(g_dir.c_str());
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t control = data[0];
  static const prm::MeshFormat kFormats[8] = {prm::MeshFormat::Ply,  prm::MeshFormat::Obj,  prm::MeshFormat::Off,
                                              prm::MeshFormat::Stl,  prm::MeshFormat::Gltf, prm::MeshFormat::Glb,
                                              prm::MeshFormat::Auto, prm::MeshFormat::Auto};
  static const char* const kExt[8] = {"ply", "obj", "off", "stl", "gltf", "glb", "bin", "bin"};
  prm::ReadOptions opt;
  opt.format = kFormats[control & 7];
  if (control & 8) {
    opt.weld = prm::ReadOptions::Weld::Always;
    opt.weld_tolerance = 1e-3;
  }
  opt.keep_properties = !(control & 16);
  const std::string path = write_input(data + 1, size - 1, kExt[control & 7]);
  try {
    prm::ReadReport report;
    const prm::Mesh mesh = prm::read_mesh(path, opt, &report);
    for (const prm::Tri& t : mesh.triangles)
      for (uint32_t v : t)
        if (v >= mesh.positions.size()) __builtin_trap();
    for (const prm::Vec3& p : mesh.positions)
      for (double c : p)
        if (!std::isfinite(c)) __builtin_trap();
  } catch (const prm::InputError&) {
  } catch (const prm::IoError&) {
  }
  return 0;
}
