#!/usr/bin/env bash
# The relief measurement of issue 3 (bench/README.md, "Reliefs"): for every mesh of ../shared/meshes, the number
# of reliefs and the total length of relief boundaries (as a multiple of the bounding-box diagonal) at
# tau = 0.1, 0.2, 0.3, 0.4, 0.577 and for the naive layout (each triangle to the axis closest to its normal), with
# small reliefs merged as the paper's construction allows (into neighbours they face by tau), and at tau 0.2 with
# the remesher's default merge (reliefs under 256 mean triangles into neighbours they face by 0.02).
#
#   bench/relief_table.sh [PRM_BINARY] [--csv FILE]      (default binary: build/tools/prm/prm)
# Prints a Markdown table. Meshes with holes are repaired first (`prm repair`), as the remesher does.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
prm="${1:-$root/build/tools/prm/prm}"
csv=""
if [ "${2:-}" = "--csv" ]; then csv="${3:?--csv needs a file}"; fi
meshes="$(cd "$root/.." && pwd)/shared/meshes"
[ -x "$prm" ] || { echo "relief_table: $prm is not built" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

for f in "$meshes"/*.ply "$meshes"/*.off "$meshes"/*.obj; do
  name=$(basename "$f")
  in="$f"
  if ! "$prm" info "$f" --json | python3 -c 'import json,sys; d=json.load(sys.stdin); sys.exit(0 if d.get("boundary_loops",0)==0 and d.get("non_manifold_vertices",0)==0 else 1)'; then
    "$prm" repair "$f" -o "$work/$name.ply" >/dev/null 2>&1 || { echo "relief_table: $name cannot be repaired, skipped" >&2; continue; }
    in="$work/$name.ply"
  fi
  diag=$("$prm" info "$in" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["diagonal"])')
  # The paper's construction (small reliefs merge only into neighbours they face by tau), then the default merge
  # (reliefs under 256 mean triangles join a neighbour all their faces face by 0.02) at tau 0.2: "0.2+merge".
  for tau in 0.1 0.2 0.3 0.4 0.577 naive 0.2+merge; do
    if [ "$tau" = naive ]; then args=(--naive)
    elif [ "$tau" = 0.2+merge ]; then args=(--tau 0.2)
    else args=(--tau "$tau" --min-relief 16 --merge-facing "$tau"); fi
    "$prm" reliefs "$in" -o "$work/r.ply" "${args[@]}" --json |
      python3 -c 'import json,sys; d=json.load(sys.stdin); print(sys.argv[1], sys.argv[2], len(d["relief_list"]), d["boundary_length"]/float(sys.argv[3]), 1000 * d["seconds"])' "$name" "$tau" "$diag"
  done
done > "$work/rows.txt"

python3 - "$work/rows.txt" "$csv" <<'PY'
import sys, collections
rows = [l.split() for l in open(sys.argv[1])]
taus = ["0.1", "0.2", "0.3", "0.4", "0.577", "naive", "0.2+merge"]
by = collections.OrderedDict()
for name, tau, n, length, ms in rows:
    by.setdefault(name, {})[tau] = (int(n), float(length), float(ms))
print("| mesh | " + " | ".join(f"reliefs τ={t}" if t != "naive" else "reliefs naive" for t in taus) + " | "
      + " | ".join(f"boundary τ={t}" if t != "naive" else "boundary naive" for t in taus) + " | ms τ=0.2 |")
print("|---|" + "---:|" * (2 * len(taus) + 1))
for name, d in by.items():
    cells = [str(d[t][0]) if t in d else "" for t in taus] + [f"{d[t][1]:.1f}" if t in d else "" for t in taus]
    print(f"| {name} | " + " | ".join(cells) + f" | {d['0.2'][2]:.0f} |")
print()
print("Boundary lengths are in bounding-box diagonals; times are `prm reliefs`' own (relief construction only).")
if sys.argv[2]:
    with open(sys.argv[2], "w") as out:
        out.write("mesh,tau,reliefs,boundary_length_diagonals,milliseconds\n")
        for name, tau, n, length, ms in rows:
            out.write(f"{name},{tau},{n},{length},{ms}\n")
PY
