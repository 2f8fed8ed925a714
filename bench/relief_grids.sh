#!/bin/bash
# Issue 23: pack at a target error with one grid (today's default) and with a grid per relief (--adaptive, format
# 1.5), on the given meshes: bytes, decoded RMS and max (fractions of the diagonal), vertices, Grid_Size, grid sizes
# in the stream, CPU seconds and peak memory. Usage: bench/relief_grids.sh PRM TARGET MESH... (one row per mesh and
# mode, printed and appended to relief_grids.txt in the current folder).
set -u
P=$1; target=$2; shift 2
# MODES (default "uniform adaptive"): uniform (one grid), adaptive (--adaptive, its default model), measured and
# curvature (--adaptive --adaptive-model measured|curvature); EXTRA: more pack arguments for every run.
for mesh in "$@"; do
  for mode in ${MODES:-uniform adaptive}; do
    extra=(${EXTRA:-})
    [ $mode = adaptive ] && extra+=(--adaptive)
    [ $mode = measured ] && extra+=(--adaptive --adaptive-model measured)
    [ $mode = curvature ] && extra+=(--adaptive --adaptive-model curvature)
    tag=$(basename "${mesh%.*}")_${mode}_$target
    /usr/bin/time -f '%U %S %M' nice -n 10 "$P" pack "$mesh" --target-error "$target" "${extra[@]}" -o "$tag.prm" \
      --json > "$tag.json" 2> "$tag.time"
    python3 - "$tag" "$mode" "$target" <<'PY' | tee -a relief_grids.txt
import json, sys
tag, mode, target = sys.argv[1:4]
cpu = [l for l in open(tag + '.time').read().split('\n') if l and l[0].isdigit()][-1].split()
j = json.load(open(tag + '.json'))
print(f"{tag.rsplit('_', 2)[0]:16s} {target:7s} {mode:8s} bytes {j['bytes']['total']:7d} rms {j['distance']['rms_rel']:.4e} "
      f"max {j['distance']['max_rel']:.4e} vertices {j['vertices']:6d} grid {j['grid_steps']:3d} sizes {j['grid_sizes']} "
      f"cpu {float(cpu[0]) + float(cpu[1]):.1f} s mem {cpu[2]} KB")
PY
  done
done
