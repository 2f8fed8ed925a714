#!/usr/bin/env bash
# Builds the PRM decoder to WebAssembly with Debian's emscripten (apt `emscripten`, 3.1.6; scripts/setup.sh):
# only the prm_decoder target's sources (codec/, configured with -DPRM_CODEC_ONLY=ON) and web/wasm/prm_wasm.c.
#   web/build.sh [WORK_DIR]   WORK_DIR (default build/web-wasm) holds the emscripten CMake build;
#                             writes web/dist/prm_decoder_wasm.js and web/dist/prm_decoder_wasm.wasm
# Exit codes: 0 built, 3 emcc missing or the build failed.
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$web")"
work="${1:-$root/build/web-wasm}"
# Debian's emcc runs on the nodesource node, which does not search Debian's node modules (acorn): ECOSYSTEM.md §3.
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
if ! command -v emcc >/dev/null || ! command -v emcmake >/dev/null; then
  echo "web/build.sh: emcc not found (apt-get install emscripten, scripts/setup.sh)" >&2
  exit 3
fi
# Include directories as -iquote: emscripten's libc++ includes <limits.h>, which -I codec/src would resolve to the
# codec's own src/limits.h (GCC's libstdc++ does not); the codec includes its headers with quotes only.
# -mbulk-memory (here and at the link): memset and memcpy, which clear and copy the decoder's arrays, become the
# memory.fill / memory.copy instructions instead of loops compiled to wasm, and emscripten's memcpy no longer calls
# out to JavaScript for large copies: 472 B smaller gzipped and 1-4% faster in V8 (web/README.md, "hweb2"). Bulk
# memory is in Chrome 75, Firefox 79, Safari 15 and later.
wasm_features="-mbulk-memory"
emcmake cmake -S "$root" -B "$work" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPRM_CODEC_ONLY=ON -DPRM_BUILD_TESTS=OFF \
  -DPRM_BUILD_BENCH=OFF "-DCMAKE_INCLUDE_FLAG_CXX=-iquote " "-DCMAKE_C_FLAGS=$wasm_features" \
  "-DCMAKE_CXX_FLAGS=$wasm_features" >"$work.configure.log" 2>&1 || { cat "$work.configure.log" >&2; exit 3; }
cmake --build "$work" --target prm_decoder -j "${PRM_WEB_JOBS:-2}" || exit 3
mkdir -p "$web/dist"
exports="_malloc,_free"
for f in decode mesh_vertices mesh_triangles mesh_positions mesh_quantized mesh_indices mesh_bits mesh_origin \
         mesh_step mesh_free error_new error_free error_status error_name error_offset error_section error_message; do
  exports="$exports,_prm_wasm_$f"
done
# MODULARIZE + EXPORT_ES6: a factory the ES module imports; web,worker: the page and its Web Worker (node tests hand
# the module the .wasm bytes, so the loader never fetches). Exceptions stay disabled: the decoder catches only
# bad_alloc, and an allocation failure aborts the instance instead. emmalloc: 1.9 kB smaller gzipped than dlmalloc.
# Binaryen's -O3 inlines every function that has one caller, whatever its size: the whole decoder became one 71 kB
# function, which V8 runs in its baseline tier (Liftoff; wasm has no on-stack replacement) until its optimizing tier
# has compiled all of it: tens of decodes on a busy machine, at 10-50x the optimized time. Capping that inlining at
# 300 bytes keeps functions of at most 18 kB (optimized after a few decodes), the same optimized speed, and a
# smaller module.
emcc -O3 -flto -DPRM_STATIC_DEFINE -I"$root/codec/include" -I"$work/include" "$web/wasm/prm_wasm.c" \
  "$work/codec/libprm_decoder.a" -o "$web/dist/prm_decoder_wasm.js" \
  -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=createPrmModule -sENVIRONMENT=web,worker -sALLOW_MEMORY_GROWTH=1 \
  -sFILESYSTEM=0 -sMALLOC=emmalloc -sEXPORTED_FUNCTIONS="$exports" -sEXPORTED_RUNTIME_METHODS=UTF8ToString \
  -sBINARYEN_EXTRA_PASSES=--one-caller-inline-max-function-size=300 $wasm_features || exit 3
echo "web/build.sh: $(stat -c %s "$web/dist/prm_decoder_wasm.wasm") B web/dist/prm_decoder_wasm.wasm"
