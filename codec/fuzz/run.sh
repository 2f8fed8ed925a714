#!/bin/sh
# Fuzzing as a habit: builds the four codec fuzz targets and the two readers' targets (mesh_read_fuzzer:
# common/fuzz, the mesh files; gltf_ext_fuzzer: gltf_ext/fuzz, a .glb with PRM streams) with clang and libFuzzer, seeds a kept corpus per target,
# fuzzes each target in turn (one process, niced) with a fast UBSan build, then runs every unit of its corpus once
# under ASan+UBSan. Totals per target are appended to a log.
#
#   codec/fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]      (default: 300 s each, all six targets)
#   codec/fuzz/run.sh 0 [TARGET...]                         (no fuzzing: the ASan pass over the kept corpora only)
#
# Two builds (codec/fuzz/README.md says why): $FUZZ_DIR/ubsan, UBSan only, for throughput, and $FUZZ_DIR/asan,
# ASan+UBSan, for the pass over the corpus (memory errors that UBSan cannot see). Both trace comparisons in the
# container code only (PRM_FUZZ_TRACE_CMP_CONTAINER_ONLY): elsewhere comparison tracing cost about 60% of an execution
# and guides no mutation, since range-coded bytes are never compared as they are.
#
# Environment: FUZZ_DIR (default build-fuzz: build trees, corpora, artifacts, log), PRM (a built `prm` tool for the
# real PRM seeds; default build/tools/prm/prm, skipped with a note when absent), RSS_MB (default 1024: the decoder's
# memory follows what it decodes, spec §4.5, so a larger footprint is a finding), JOBS (build jobs, default 2),
# NICE (default 15), RUNS (when set, stop each target after this many executions, or at SECONDS if that is not 0 and
# comes first),
# ASAN_PASS (default 1; 0 skips the ASan pass), LOG_TAG (names this run's libFuzzer log, so that two runs of a target,
# one per core, can share its corpus: libFuzzer adds units under content-hash names).
#
# Corpora live in $FUZZ_DIR/corpus/<target>/ and grow from run to run (they stay out of git); crashes, leaks, timeouts
# and out-of-memory inputs land in $FUZZ_DIR/artifacts/. Each run appends one line per target and pass to
# $FUZZ_DIR/fuzz-log.tsv: date, commit, build, target, executions, seconds, executions per second, finding.
# `codec/fuzz/totals.sh` sums the log per target; codec/fuzz/README.md records the totals.
set -eu

seconds=${1:-300}
[ $# -gt 0 ] && shift
targets=${*:-"decode_fuzzer range_coder_fuzzer roundtrip_fuzzer prm_roundtrip_fuzzer mesh_read_fuzzer gltf_ext_fuzzer"}
root=$(cd "$(dirname "$0")/../.." && pwd)
fuzz_dir=${FUZZ_DIR:-$root/build-fuzz}
prm=${PRM:-$root/build/tools/prm/prm}
rss_mb=${RSS_MB:-1024}
jobs=${JOBS:-2}
niceness=${NICE:-15}
runs=${RUNS:-}
asan_pass=${ASAN_PASS:-1}

command -v clang++ >/dev/null || { echo "run.sh: clang++ is needed (libFuzzer)" >&2; exit 3; }
launcher=""
command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
set --
for t in $targets; do set -- "$@" "prm_fuzz_$t"; done
builds="ubsan"
[ "$asan_pass" = 1 ] && builds="ubsan asan"
for b in $builds; do
  san=undefined
  [ "$b" = asan ] && san=address,undefined
  cmake -S "$root" -B "$fuzz_dir/$b" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ $launcher \
        -DPRM_BUILD_FUZZERS=ON -DPRM_FUZZ_TRACE_CMP_CONTAINER_ONLY=ON -DPRM_SANITIZE=$san -DPRM_BUILD_TESTS=OFF \
        -DPRM_BUILD_BENCH=OFF >/dev/null
  nice -n "$niceness" cmake --build "$fuzz_dir/$b" -j "$jobs" --target "$@"
done

mkdir -p "$fuzz_dir/artifacts"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Seeds of the decode fuzzer: every conformance stream (valid and invalid) and real PRM streams made now, each behind
# the control byte 0x01 (the fuzzer fixes the CRC up when the first byte is odd).
seed_decode() {
  dir=$1
  for s in "$root"/conformance/vectors/*/stream.prm "$root"/conformance/invalid/*/stream.prm; do
    [ -f "$s" ] || continue
    name=$(basename "$(dirname "$s")")
    (printf '\001'; cat "$s") >"$dir/seed-$name"
  done
  if [ -x "$prm" ]; then
    meshes=$root/../shared/meshes
    for m in spot.obj feline_5k.obj rabbit_1k_decimated.off; do
      [ -f "$meshes/$m" ] || continue
      # made once: the corpus is kept, and a pack takes a while
      if [ ! -f "$dir/seed-pack-$m" ] &&
         nice -n "$niceness" "$prm" pack "$meshes/$m" -o "$tmp/s.prm" --target-error 1e-3 >/dev/null 2>&1; then
        (printf '\001'; cat "$tmp/s.prm") >"$dir/seed-pack-$m"
      fi
      if [ ! -f "$dir/seed-encode-$m" ] &&
         nice -n "$niceness" "$prm" encode "$meshes/$m" -o "$tmp/s.prm" --bits 10 >/dev/null 2>&1; then
        (printf '\001'; cat "$tmp/s.prm") >"$dir/seed-encode-$m"
      fi
    done
  else
    echo "run.sh: no prm tool at $prm: the decode corpus gets the conformance streams only" >&2
  fi
}

# Seeds of the mesh read fuzzer, each behind its control byte (common/fuzz/mesh_read_fuzzer.cpp: 0 PLY, 1 OBJ, 2 OFF,
# 3 STL, 4 glTF, 5 GLB, 6 sniffed): the small hand-made files of common/tests/data (valid and hostile), and a real
# mesh made small now (rabbit_1k_decimated packed at 1e-2, decoded to PLY, OBJ, OFF, glTF and GLB), also sniffed.
seed_mesh_read() {
  dir=$1
  for s in "$root"/common/tests/data/*; do
    b=""
    case $s in
      *.ply) b='\000' ;; *.obj) b='\001' ;; *.off) b='\002' ;; *.stl) b='\003' ;; *.gltf) b='\004' ;; *.glb) b='\005' ;;
    esac
    [ -n "$b" ] || continue
    (printf "$b"; cat "$s") >"$dir/seed-$(basename "$s")"
  done
  m=$root/../shared/meshes/rabbit_1k_decimated.off
  if [ -x "$prm" ] && [ -f "$m" ] && [ ! -f "$dir/seed-rabbit.ply" ] &&
     nice -n "$niceness" "$prm" pack "$m" -o "$tmp/r.prm" --target-error 1e-2 >/dev/null 2>&1; then
    for e in ply:000 obj:001 off:002 gltf:004 glb:005; do
      "$prm" decode "$tmp/r.prm" -o "$tmp/r.${e%%:*}" >/dev/null 2>&1 || continue
      (printf "\\${e#*:}"; cat "$tmp/r.${e%%:*}") >"$dir/seed-rabbit.${e%%:*}"
      (printf '\006'; cat "$tmp/r.${e%%:*}") >"$dir/seed-rabbit-sniffed.${e%%:*}"
    done
  fi
}

# Seeds of the glTF extension fuzzer (gltf_ext/fuzz/gltf_ext_fuzzer.cpp; control byte 0: a .glb, read and unpacked to
# a .glb): assets with PRM streams made now by `prm pack` of rabbit_1k_decimated (with and without --fallback, GLB and
# .gltf) and of the hand-made tet.glb, and the GLBs of common/tests/data.
seed_gltf_ext() {
  dir=$1
  for s in "$root"/common/tests/data/*.glb; do (printf '\000'; cat "$s") >"$dir/seed-$(basename "$s")"; done
  [ -x "$prm" ] || return 0
  for m in "$root"/../shared/meshes/rabbit_1k_decimated.off "$root"/common/tests/data/tet.glb; do
    [ -f "$m" ] || continue
    n=$(basename "$m")
    for v in glb: glb:--fallback gltf: gltf:--fallback; do
      out=$dir/seed-pack-$n${v#*:}.${v%%:*}
      [ -f "$out" ] && continue
      # shellcheck disable=SC2086
      nice -n "$niceness" "$prm" pack "$m" -o "$tmp/p.${v%%:*}" --target-error 1e-2 ${v#*:} >/dev/null 2>&1 || continue
      c='\000'
      [ "${v%%:*}" = gltf ] && c='\001'
      (printf "$c"; cat "$tmp/p.${v%%:*}") >"$out"
    done
  done
}

# One line of the log from libFuzzer's final statistics in $1 (build $2, target $3, exit status $4, seconds asked $5).
log_line() {
  n=$(sed -n 's/^stat::number_of_executed_units: *//p' "$1" | tail -n 1)
  secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$1" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$1" | tail -n 1)
  finding=none
  [ "$4" -ne 0 ] && finding="exit $4: $(grep -m 1 -E 'ERROR|SUMMARY|Test unit written' "$1" || true)"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%Y-%m-%dT%H:%MZ)" "$commit" "$2" "$3" "${n:-?}" \
      "${secs:-$5}" "${rate:-?}" "$finding" | tee -a "$fuzz_dir/fuzz-log.tsv"
}

# Where a target's binary is in a build tree.
target_dir() {
  case $1 in
    mesh_read_fuzzer) echo common ;;
    gltf_ext_fuzzer) echo tools/prm ;;
    *) echo codec ;;
  esac
}

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
for t in $targets; do
  corpus=$fuzz_dir/corpus/$t
  mkdir -p "$corpus"
  extra=""
  if [ "$t" = decode_fuzzer ]; then
    seed_decode "$corpus"
    extra="-max_len=12288"  # the largest seed (feline_5k encoded at 10 bits) is 10.7 KB
  fi
  [ "$t" = prm_roundtrip_fuzzer ] && extra="-max_len=64 -len_control=0"
  if [ "$t" = mesh_read_fuzzer ]; then
    seed_mesh_read "$corpus"
    extra="-max_len=16384"  # the largest seed (the rabbit as OBJ/OFF) is 8.8 KB
  fi
  if [ "$t" = gltf_ext_fuzzer ]; then
    seed_gltf_ext "$corpus"
    extra="-max_len=16384"
  fi
  limit=""  # whichever comes first
  [ "$seconds" != 0 ] && limit="-max_total_time=$seconds"
  [ -n "$runs" ] && limit="$limit -runs=$runs"
  log=$fuzz_dir/$t${LOG_TAG:+.$LOG_TAG}.log  # LOG_TAG: several runs of one target side by side (one per core)
  if [ "$seconds" != 0 ] || [ -n "$runs" ]; then
    echo "== $t: $limit, corpus $corpus" >&2
    status=0
    # shellcheck disable=SC2086
    nice -n "$niceness" "$fuzz_dir/ubsan/$(target_dir "$t")/prm_fuzz_$t" $limit -rss_limit_mb="$rss_mb" -timeout=20 \
        -print_final_stats=1 -artifact_prefix="$fuzz_dir/artifacts/$t-" $extra "$corpus" >"$log" 2>&1 || status=$?
    log_line "$log" ubsan "$t" "$status" "$seconds"
  fi
  [ "$asan_pass" = 1 ] || continue
  # Every unit of the corpus once under ASan+UBSan (-runs=0: read, execute, stop; nothing is added).
  echo "== $t: ASan pass over corpus $corpus" >&2
  status=0
  # shellcheck disable=SC2086
  nice -n "$niceness" "$fuzz_dir/asan/$(target_dir "$t")/prm_fuzz_$t" -runs=0 -rss_limit_mb="$rss_mb" -timeout=60 \
      -print_final_stats=1 -artifact_prefix="$fuzz_dir/artifacts/$t-asan-" $extra "$corpus" >"$log.asan" 2>&1 ||
      status=$?
  log_line "$log.asan" asan-corpus "$t" "$status" 0
done
