#!/usr/bin/env bash
# Installs every Debian package that PRM's build, tests, benches and demo need.
# Usage: scripts/setup.sh [--with-meshlab]
# Non-interactive, idempotent (skips what is installed), Debian 12; run as root or with sudo available.
# Nothing is fetched from anywhere but Debian's package archive, and the Khronos glTF-Validator from the npm
# registry (tools/gltf_validator, pinned by its package-lock.json).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  clang libclang-rt-14-dev            # libFuzzer and the sanitizer runtime for clang builds
  libgtest-dev libgmock-dev libbenchmark-dev
  libdraco-dev draco                  # the baseline we compare against; Draco-compressed glTF input
  libmeshoptimizer-dev                # EXT_meshopt_compression glTF input (meshopt's decoders; its encoder in tests)
  libtinygltf-dev nlohmann-json3-dev libstb-dev   # glTF I/O (compiled privately), JSON output, PNG writing
  libtinyobjloader-dev                # OBJ reading
  libcli11-dev                        # the command line
  libtbb-dev                          # parallel loops in the remesher and the metric
  libopenmesh-dev                     # half-edge mesh for the remesher's collapses and flips
  libcgal-demo                        # CGAL's data set: real meshes for tests and benches
  python3                             # bench scripts' tables
  gnuplot-nox                         # bench scripts' plots (bench/scale_plot.gp: PNG through pngcairo)
  emscripten chromium                 # web/: the decoder in WebAssembly, the viewer's headless browser test
)
# The Khronos glTF-Validator (npm, run by the glTF tests) needs node and npm: Debian's, unless some node is there.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
# --with-meshlab: also MeshLab (GPL; an independent reference for bench/metro_crosscheck.sh, never linked) and the
# virtual X server it needs.
if [ "${1:-}" = "--with-meshlab" ]; then packages+=(meshlab xvfb xauth); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages are installed"
else
  echo "setup: installing ${#missing[@]} missing packages: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The validator itself, from the npm registry into tools/gltf_validator/node_modules (version pinned by its lock file).
validator_dir="$(cd "$(dirname "$0")/.." && pwd)/tools/gltf_validator"
if [ ! -d "$validator_dir/node_modules/gltf-validator" ]; then
  echo "setup: installing the glTF validator into $validator_dir/node_modules"
  (cd "$validator_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi
# web/'s npm packages (three, puppeteer-core; pinned by web/package-lock.json). puppeteer-core downloads no browser:
# the tests drive Debian's /usr/bin/chromium.
web_dir="$(cd "$(dirname "$0")/.." && pwd)/web"
if [ ! -d "$web_dir/node_modules/three" ] || [ ! -d "$web_dir/node_modules/puppeteer-core" ]; then
  echo "setup: installing web/'s npm packages into $web_dir/node_modules"
  (cd "$web_dir" && PUPPETEER_SKIP_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
fi
echo "setup: done"
