#!/usr/bin/env bash
# Issue 17's zero-area sweep: `prm pack` at two target errors on the shared meshes, CGAL's dense ones (over 5k
# vertices) and three awkward cases (a bowtie, CGAL's elephant.off, a 1 x 1 x 0.002 box), each stream decoded and
# checked against what pack remeshed (prm_bench_stream_check): triangles of exactly zero area (integer test on the
# decoded coordinates), decoded vertices that share a position, triangles facing away from the input, exit code.
# One row per pack, printed as it finishes (a Markdown table); CPU seconds of the pack from /usr/bin/time.
# Usage: bench/zero_area_sweep.sh PRM_BINARY STREAM_CHECK_BINARY [CGAL_MESH_DIR] [TARGETS]
#   e.g. bench/zero_area_sweep.sh build/tools/prm/prm build/bench/prm_bench_stream_check
set -uo pipefail
prm=${1:?usage: zero_area_sweep.sh PRM_BINARY STREAM_CHECK_BINARY [CGAL_MESH_DIR] [TARGETS]}
check=${2:?usage: zero_area_sweep.sh PRM_BINARY STREAM_CHECK_BINARY [CGAL_MESH_DIR] [TARGETS]}
here=$(cd "$(dirname "$0")/.." && pwd)
cgal=${3:-$(dirname "$prm")/../../cgal-data/data/meshes}
targets=${4:-"2e-4 1e-4"}
shared="$here/../shared/meshes"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The awkward cases, written as OFF: two triangles sharing a vertex; a 1 x 1 x 0.002 box of 10 x 10 quads a side.
python3 - "$tmp" <<'PY'
import sys
d = sys.argv[1]
with open(d + "/bowtie.off", "w") as f:
    f.write("OFF\n5 2 0\n0 0 0\n1 0.5 0\n1 -0.5 0\n-1 0.5 0\n-1 -0.5 0\n3 0 1 2\n3 0 3 4\n")
n, size = 10, (1.0, 1.0, 0.002)
ids, pts, tris = {}, [], []
def vid(g):
    if g not in ids:
        ids[g] = len(pts)
        pts.append(tuple(size[a] * g[a] / n for a in range(3)))
    return ids[g]
for axis in range(3):
    for side in range(2):
        for i in range(n):
            for j in range(n):
                def at(u, w):
                    g = [0, 0, 0]
                    g[axis] = side * n
                    g[(axis + 1) % 3] = u
                    g[(axis + 2) % 3] = w
                    return vid(tuple(g))
                a, b, c, e = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
                tris += [(a, b, c), (a, c, e)] if side else [(a, c, b), (a, e, c)]
with open(d + "/thin_box.off", "w") as f:
    f.write("OFF\n%d %d 0\n" % (len(pts), len(tris)))
    f.writelines("%.17g %.17g %.17g\n" % p for p in pts)
    f.writelines("3 %d %d %d\n" % t for t in tris)
PY

meshes=("$tmp/bowtie.off" "$tmp/thin_box.off" "$cgal/elephant.off")  # then by size
for f in rabbit_1k_decimated.off spot.obj feline_5k.obj fandisk.obj rocker-arm.off; do meshes+=("$shared/$f"); done
for f in ChineseDragon-10kv.off camel.off mannequin-devil.off man.off diplodocus.off armadillo.off; do
  meshes+=("$cgal/$f")
done
meshes+=("$shared/bunny_zipper.ply" "$cgal/bunny00.off" "$cgal/refined_elephant.off")
for f in horse.ply feline.off venus.off igea.ply; do meshes+=("$shared/$f"); done

printf '| mesh | target | exit | bits | bytes | decoded V | zero-area | coincident V | turned | CPU s |\n'
printf '|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n'
bad=0
for f in "${meshes[@]}"; do
  [ -e "$f" ] || { echo "| $(basename "$f") | missing |"; continue; }
  for t in $targets; do
    /usr/bin/time -o "$tmp/time" -f '%U %S' "$prm" pack "$f" --target-error "$t" -o "$tmp/out.prm" --json \
      > "$tmp/pack.json" 2> "$tmp/err"
    rc=$?
    cpu=$(tail -n 1 "$tmp/time" | awk '{printf "%.0f", $1 + $2}')
    if [ $rc -ne 0 ]; then
      printf '| %s | %s | %d | | | | | | | %s |\n' "$(basename "$f")" "$t" "$rc" "$cpu"
      tr '\n' ' ' < "$tmp/err" | head -c 200 | sed 's/^/<!-- /; s/$/ -->\n/'
      [ $rc -eq 3 ] || bad=$((bad + 1))  # 3: the target cannot be reached (documented); anything else is a failure
      continue
    fi
    bits=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["bits"], d["bytes"]["total"])' "$tmp/pack.json")
    read -r zero coincident turned nv nt < <("$check" "$f" "$tmp/out.prm") || { zero=DECODE; bad=$((bad + 1)); }
    printf '| %s | %s | %d | %s | %s | %s | %s | %s | %s | %s |\n' "$(basename "$f")" "$t" "$rc" \
      ${bits% *} ${bits#* } "$nv" "$zero" "$coincident" "$turned" "$cpu"
    [ "$zero" = 0 ] && [ "$coincident" = 0 ] || bad=$((bad + 1))
  done
done
echo
echo "packs with a zero-area triangle, coincident vertices, a stream that does not decode or an undocumented exit: $bad"
[ $bad -eq 0 ]
