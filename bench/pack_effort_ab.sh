#!/bin/bash
# pack effort (issue 21): CPU seconds, stream bytes and RMS of `prm pack` on the four 50k-vertex paper models, for
# one binary (the state) or two (before / after, run alternately so that both see the same load), REPS runs each.
#
#   bench/pack_effort_ab.sh OUTDIR REPS "EFFORTS" PRM_BEFORE [PRM_AFTER]
#   e.g. bench/pack_effort_ab.sh /tmp/ab 2 "0 3" ../main-old/build/tools/prm/prm build/tools/prm/prm
#
# Run from the checkout's root (the meshes are ../shared/meshes). Each run is
#   /usr/bin/time -f '%U %S %M' nice -n 10 PRM pack MESH --target-error E --effort N -o OUT.prm --json
# and prints one line: binary, run, effort, model, exit code, CPU s (user + system), peak kB, bytes, RMS / diagonal,
# grid steps, remesh rounds, the load average, and with two binaries whether the two streams of this run are
# `cmp`-identical. Exit code 1 on a bad command line, 3 when a pack fails.
set -u
if [ $# -lt 4 ] || [ $# -gt 5 ]; then
  sed -n '2,13p' "$0" >&2
  exit 1
fi
out=$1 reps=$2 efforts=$3
bins=("$4")
[ $# -eq 5 ] && bins+=("$5")
mkdir -p "$out" || exit 1
models="horse.ply:2e-4 venus.off:1.3e-4 feline.off:2.6e-4 bunny_zipper.ply:2e-4"  # the targets of Table 1
failed=0
field() {  # field JSON KEY: a top-level number of a pack --json report
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d$2)" "$1" 2>/dev/null || echo "?"
}
for ((rep = 1; rep <= reps; rep++)); do
  for eff in $efforts; do
    for m in $models; do
      f=${m%%:*} e=${m##*:}
      for ((b = 0; b < ${#bins[@]}; b++)); do
        run=$out/b${b}_r${rep}_e${eff}_${f%%.*}
        /usr/bin/time -f '%U %S %M' -o "$run.time" nice -n 10 "${bins[$b]}" pack "../shared/meshes/$f" \
          --target-error "$e" --effort "$eff" -o "$run.prm" --json >"$run.json" 2>"$run.err"
        rc=$?
        [ $rc -ne 0 ] && failed=1
        read -r user sys peak <"$run.time"
        cpu=$(python3 -c "print(f'{$user + $sys:.2f}')")
        same=""
        if [ $b -eq 1 ]; then
          cmp -s "$out/b0_r${rep}_e${eff}_${f%%.*}.prm" "$run.prm" && same="cmp-identical" || same="differs"
        fi
        echo "b$b r$rep e$eff ${f%%.*} rc=$rc cpu=$cpu peak_kB=$peak bytes=$(field "$run.json" "['bytes']['total']")" \
          "rms=$(field "$run.json" "['distance']['rms_rel']") grid_steps=$(field "$run.json" "['grid_steps']")" \
          "rounds=$(field "$run.json" "['remesh_rounds']") load=$(cut -d' ' -f1 /proc/loadavg) $same"
      done
    done
  done
done
[ $failed -eq 0 ] || exit 3
