#!/usr/bin/env bash
# bench/entropy_study/build_wasm.sh [WORK_DIR]: prm_bench_entropy_study built with emscripten for node (bench/README.md,
# "hdecode8"): the codec's decoder sources five times (the library's, traced, oracle, values, rans: the variants of
# bench/CMakeLists.txt), -O3 and bulk memory as web/build.sh's codec, no LTO. Needs the native configure's
# build/include (prm/version.h). Writes WORK_DIR/study.js and study.wasm (default build/entropy-study-wasm); run with
#   node --no-experimental-fetch WORK_DIR/study.js [--check | --rounds=N] FILE.prm...
# (emscripten 3.1.6's loader fetches the .wasm when node has fetch). Times are wall clock there: no thread CPU clock.
# Exit codes: 0 built, 3 em++ missing or a compile failed.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
work="${1:-$root/build/entropy-study-wasm}"
mkdir -p "$work/obj"
command -v em++ >/dev/null || { echo "build_wasm.sh: em++ not found" >&2; exit 3; }
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
cc() { em++ -O3 -std=c++17 -mbulk-memory -DNDEBUG -DPRM_STATIC_DEFINE -iquote "$root/codec/src" \
  -iquote "$root/bench/entropy_study" -I"$root/codec/include" -I"$root/build/include" "$@" || exit 3; }
decoder="clers_decode codec_api_decode container_decode corner_table crc32 lers_decode patch_decode position_decode
         range_decoder spirale_reversi stream_reader"
declare -A defs=([lib]="" [traced]="-DPRM_ENTROPY_TRACE" [oracle]="-DPRM_ENTROPY_ORACLE"
                 [values]="-DPRM_ENTROPY_ORACLE -DPRM_ENTROPY_VALUE_ORACLE"
                 [rans]="-DPRM_ENTROPY_ORACLE -DPRM_ENTROPY_VALUE_ORACLE -DPRM_ENTROPY_RANS")
for v in lib traced oracle values rans; do
  ns=""; [ "$v" = lib ] || ns="-Dprm=prm_$v"
  for s in $decoder; do cc -DPRM_BUILDING_LIBRARY $ns ${defs[$v]} -c "$root/codec/src/$s.cpp" -o "$work/obj/${v}_$s.o"; done
done
cc -DPRM_ENTROPY_TRACE -Dprm=prm_traced -c "$root/bench/entropy_study/trace_capture.cpp" -o "$work/obj/traced_extra.o"
for v in oracle values rans; do
  cc -Dprm=prm_$v ${defs[$v]} -c "$root/bench/entropy_study/oracle_decode.cpp" -o "$work/obj/${v}_extra.o"
done
cc -c "$root/codec/src/range_encoder.cpp" -o "$work/obj/lib_range_encoder.o"
cc -c "$root/bench/entropy_study/entropy_study.cpp" -o "$work/obj/main.o"
em++ -O3 -mbulk-memory "$work"/obj/*.o -o "$work/study.js" -sENVIRONMENT=node -sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1 \
  -sINITIAL_MEMORY=134217728 || exit 3
echo "build_wasm.sh: $work/study.js"
