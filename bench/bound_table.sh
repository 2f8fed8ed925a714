#!/bin/sh
# Issue 22's closing table: per mesh, `prm pack` at the default (the local refinement on) against
# `--no-local-refinement` (before it was the default): boundary loops in/out, the mode chosen, n_r/n_o, and bytes,
# RMS and max (sampled Hausdorff) error as fractions of the diagonal, max/target, and the bytes' ratio.
# Usage: bench/bound_table.sh PRM TARGET MESH...   (prints a Markdown table; bench/README.md "Where the bound stands")
set -eu
prm=$1; target=$2; shift 2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| mesh | loops in/out | mode | n_r/n_o | before: bytes, RMS, max (x) | after: bytes, RMS, max (x) | bytes after/before |"
echo "|---|---|---|---|---|---|---|"
for mesh in "$@"; do
  "$prm" pack "$mesh" --target-error "$target" -o "$out/a.prm" --json > "$out/a.json"
  "$prm" pack "$mesh" --target-error "$target" --no-local-refinement -o "$out/b.prm" --json > "$out/b.json"
  python3 - "$mesh" "$target" "$out/a.json" "$out/b.json" <<'PY'
import json, os, sys
mesh, target, a, b = sys.argv[1], float(sys.argv[2]), json.load(open(sys.argv[3])), json.load(open(sys.argv[4]))
def f(d):
    e = d['distance']
    return "%d B, %.3e, %.3e (%.2fx)" % (d['bytes']['total'], e['rms_rel'], e['max_rel'], e['max_rel'] / target)
name = os.path.splitext(os.path.basename(mesh))[0]
print(f"| {name} | {a['boundary_loops_in']}/{a['boundary_loops_out']} | {a['mode']} | {a['n_r']:,}/{a['n_o']:,} = "
      f"{a['n_r_over_n_o']:.3f} | {f(b)} | {f(a)} | {a['bytes']['total'] / b['bytes']['total']:.3f} |")
PY
done
