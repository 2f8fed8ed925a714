#!/usr/bin/env bash
# The remesher's table of issue 4 (bench/README.md, "Remesher"): for every mesh of ../shared/meshes and target
# RMS errors 1e-4, 2e-4 and 5e-4 of the bounding-box diagonal, `prm remesh --target-error E`'s grid size g,
# n_o, n_r, the share of regular triangles, the number of regular patches, the RMS and maximum distance of the
# PRM to the (repaired) input, the max over the target, the vertices the local refinement inserted (issue 22: by
# default with --target-error), flipped/unrepaired triangles and the wall time (grid search included).
#
#   bench/remesh_table.sh [PRM_BINARY] [--csv FILE] [--targets "1e-4 2e-4 5e-4"] [--meshes "horse venus"]
#                         [--extra "--no-local-refinement"]   (more arguments for every `prm remesh`)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
prm="${1:-$root/build/tools/prm/prm}"
shift || true
csv=""
targets="1e-4 2e-4 5e-4"
only=""
extra=""
while [ $# -gt 0 ]; do
  case "$1" in
    --csv) csv="$2"; shift 2 ;;
    --targets) targets="$2"; shift 2 ;;
    --meshes) only="$2"; shift 2 ;;
    --extra) extra="$2"; shift 2 ;;
    *) echo "remesh_table: unknown option $1" >&2; exit 1 ;;
  esac
done
meshes="$(cd "$root/.." && pwd)/shared/meshes"
[ -x "$prm" ] || { echo "remesh_table: $prm is not built" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for f in "$meshes"/*.ply "$meshes"/*.off "$meshes"/*.obj; do
  name=$(basename "$f")
  if [ -n "$only" ]; then
    keep=0; for o in $only; do case "$name" in *"$o"*) keep=1 ;; esac; done
    [ $keep = 1 ] || continue
  fi
  for t in $targets; do
    echo "remesh_table: $name at $t" >&2
    if "$prm" remesh "$f" -o "$work/out.ply" --target-error "$t" $extra --json > "$work/r.json" 2> "$work/err.txt"; then
      python3 - "$name" "$t" "$work/r.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[3]))
print(json.dumps({"mesh": sys.argv[1], "target": float(sys.argv[2]), "ok": True, "g": d["grid_size"],
                  "g_rel": d["grid_fraction"], "n_o": d["n_o"], "n_r": d["n_r"], "regular": d["regular_share"],
                  "patches": d.get("regular_patches", -1), "rms": d["distance"]["rms_rel"], "max": d["distance"]["max_rel"],
                  "refined": d.get("refined_vertices", 0), "unrepaired": d["unrepaired_triangles"],
                  "seconds": d["seconds"]}))
PY
    else
      python3 -c 'import json,sys; print(json.dumps({"mesh": sys.argv[1], "target": float(sys.argv[2]), "ok": False, "why": open(sys.argv[3]).read().strip()[-200:]}))' "$name" "$t" "$work/err.txt"
    fi
  done
done > "$work/rows.jsonl"

python3 - "$work/rows.jsonl" "$csv" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
print("| mesh | target | g | g/diag | n_o | n_r | n_r/n_o | regular | patches | RMS/diag | max/diag | max/target | refined "
      "| unrepaired | s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in rows:
    if not r["ok"]:
        print(f"| {r['mesh']} | {r['target']:.0e} | not reached: {r['why'].splitlines()[-1] if r['why'] else ''} |||||||||||||")
        continue
    patches = str(r["patches"]) if r["patches"] >= 0 else ""
    print(f"| {r['mesh']} | {r['target']:.0e} | {r['g']:.4g} | {r['g_rel']:.5f} | {r['n_o']} | {r['n_r']} | "
          f"{r['n_r']/r['n_o']:.2f} | {100*r['regular']:.1f}% | {patches} | {r['rms']:.3e} | {r['max']:.3e} | "
          f"{r['max']/r['target']:.1f} | {r['refined']} | {r['unrepaired']} | {r['seconds']:.1f} |")
if sys.argv[2]:
    keys = ["mesh", "target", "ok", "g", "g_rel", "n_o", "n_r", "regular", "patches", "rms", "max", "refined", "unrepaired", "seconds"]
    with open(sys.argv[2], "w") as out:
        out.write(",".join(keys) + "\n")
        for r in rows:
            out.write(",".join(str(r.get(k, "")) for k in keys) + "\n")
PY
