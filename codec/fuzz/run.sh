#!/bin/sh
# Fuzzing as a habit: builds the four codec fuzz targets with clang (ASan+UBSan, libFuzzer) in their own build
# directory, seeds a kept corpus per target, and runs the targets one after the other, niced, for SECONDS each.
#
#   codec/fuzz/run.sh [SECONDS_PER_TARGET] [TARGET...]      (default: 300 s each, all four targets)
#
# Environment: FUZZ_DIR (default build-fuzz: build tree, corpora, artifacts, log), PRM (a built `prm` tool for the
# real PRM seeds; default build/tools/prm/prm, skipped with a note when absent), RSS_MB (default 1024: the decoder's
# memory follows what it decodes, spec §4.5, so a larger footprint is a finding), JOBS (build jobs, default 2).
#
# Corpora live in $FUZZ_DIR/corpus/<target>/ and grow from run to run (they stay out of git); crashes, leaks, timeouts
# and out-of-memory inputs land in $FUZZ_DIR/artifacts/. Each run appends one line per target to $FUZZ_DIR/fuzz-log.tsv:
# date, commit, target, executions, seconds, executions per second, findings. codec/fuzz/README.md records the totals.
set -eu

seconds=${1:-300}
[ $# -gt 0 ] && shift
targets=${*:-"decode_fuzzer range_coder_fuzzer roundtrip_fuzzer prm_roundtrip_fuzzer"}
root=$(cd "$(dirname "$0")/../.." && pwd)
fuzz_dir=${FUZZ_DIR:-$root/build-fuzz}
prm=${PRM:-$root/build/tools/prm/prm}
rss_mb=${RSS_MB:-1024}
jobs=${JOBS:-2}

command -v clang++ >/dev/null || { echo "run.sh: clang++ is needed (libFuzzer)" >&2; exit 3; }
launcher=""
command -v ccache >/dev/null && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
cmake -S "$root" -B "$fuzz_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ $launcher \
      -DPRM_BUILD_FUZZERS=ON -DPRM_SANITIZE=address,undefined -DPRM_BUILD_TESTS=OFF -DPRM_BUILD_BENCH=OFF >/dev/null
set --
for t in $targets; do set -- "$@" "prm_fuzz_$t"; done
nice -n 10 cmake --build "$fuzz_dir" -j "$jobs" --target "$@"

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
         nice -n 10 "$prm" pack "$meshes/$m" -o "$tmp/s.prm" --target-error 1e-3 >/dev/null 2>&1; then
        (printf '\001'; cat "$tmp/s.prm") >"$dir/seed-pack-$m"
      fi
      if [ ! -f "$dir/seed-encode-$m" ] &&
         nice -n 10 "$prm" encode "$meshes/$m" -o "$tmp/s.prm" --bits 10 >/dev/null 2>&1; then
        (printf '\001'; cat "$tmp/s.prm") >"$dir/seed-encode-$m"
      fi
    done
  else
    echo "run.sh: no prm tool at $prm: the decode corpus gets the conformance streams only" >&2
  fi
}

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
for t in $targets; do
  corpus=$fuzz_dir/corpus/$t
  mkdir -p "$corpus"
  extra=""
  if [ "$t" = decode_fuzzer ]; then
    seed_decode "$corpus"
    extra="-max_len=8192"
  fi
  [ "$t" = prm_roundtrip_fuzzer ] && extra="-max_len=64 -len_control=0"
  log=$fuzz_dir/$t.log
  echo "== $t: $seconds s, corpus $corpus" >&2
  status=0
  # shellcheck disable=SC2086
  nice -n 10 "$fuzz_dir/codec/prm_fuzz_$t" -max_total_time="$seconds" -rss_limit_mb="$rss_mb" -timeout=20 \
      -print_final_stats=1 -artifact_prefix="$fuzz_dir/artifacts/$t-" $extra "$corpus" >"$log" 2>&1 || status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
  [ -n "$secs" ] || secs=$seconds
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  finding=none
  [ "$status" -ne 0 ] && finding="exit $status: $(grep -m 1 -E 'ERROR|SUMMARY|Test unit written' "$log" || true)"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%Y-%m-%dT%H:%MZ)" "$commit" "$t" "${runs:-?}" "$secs" \
      "${rate:-?}" "$finding" | tee -a "$fuzz_dir/fuzz-log.tsv"
done
