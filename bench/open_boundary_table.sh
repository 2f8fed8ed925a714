#!/usr/bin/env bash
# Issue 22's table (bench/README.md, "Open boundaries"): `prm pack --target-error E` on open meshes, keeping their
# boundary loops (the default) and with --fill-holes (the paper's fans): boundary loops in and out, holes filled,
# n_o, n_r, n_r / n_o, RMS and maximum error of the decoded stream (pack's own full-density Metro measure, against
# the input it remeshed: the open input, or with --fill-holes the input with its holes filled), bytes, CPU seconds
# (user + system) and peak RSS; and the distance of the decoded boundary from the input's (bench/boundary_distance.cpp:
# the RMS and the largest distance of a decoded boundary vertex to the input's boundary polyline, fractions of the
# diagonal). Rows per mesh: `open` (the default, --mode auto: the smaller of the PRM and the input coded as it is),
# `fill` (--fill-holes), `prm` (--mode prm: the remeshed stream keeping the holes) and `thin` (--mode prm
# --boundary-simplification 1: the loops thinned out within the target before remeshing).
# The meshes: bunny_zipper (5 holes), CGAL's elephant-with-holes and mech-holes-shark, and two generated here as
# in pipeline/tests/pack_open_boundary_test.cpp: an 81 x 81 height-field terrain and spot cut at mid-height.
#
#   bench/open_boundary_table.sh [PRM_BINARY] [--target E] [--cgal DIR] [--meshes "terrain bunny_zipper"]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
prm="${1:-$root/build/tools/prm/prm}"
shift || true
target="2e-4"
cgal="$root/build/cgal-data/data/meshes"
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    --target) target="$2"; shift 2 ;;
    --cgal) cgal="$2"; shift 2 ;;
    --meshes) only="$2"; shift 2 ;;
    *) echo "open_boundary_table: unknown option $1" >&2; exit 1 ;;
  esac
done
shared="$(cd "$root/.." && pwd)/shared/meshes"
[ -x "$prm" ] || { echo "open_boundary_table: $prm is not built" >&2; exit 2; }
distance="$root/build/bench/prm_bench_boundary_distance"
[ -x "$distance" ] || { echo "open_boundary_table: $distance is not built" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The generated meshes (the same as the test's).
python3 - "$work" "$shared/spot.obj" <<'EOF'
import math, sys
work, spot = sys.argv[1], sys.argv[2]
n = 80
with open(f"{work}/terrain.obj", "w") as o:
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            o.write(f"v {x!r} {y!r} {0.08 * math.sin(5 * x) * math.cos(4 * y) + 0.05 * math.sin(11 * x + 3 * y)!r}\n")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            o.write(f"f {a} {a + 1} {a + n + 2}\nf {a} {a + n + 2} {a + n + 1}\n")
pos, tris = [], []
for line in open(spot):
    w = line.split()
    if not w: continue
    if w[0] == "v": pos.append([float(c) for c in w[1:4]])
    elif w[0] == "f": tris.append([int(c.split("/")[0]) - 1 for c in w[1:4]])
zs = [p[2] for p in pos]
mid = 0.5 * (min(zs) + max(zs))
ids = {}
with open(f"{work}/spot_cut.obj", "w") as o:
    out = []
    for t in tris:
        if sum(pos[v][2] for v in t) / 3 > mid: continue
        for v in t:
            if v not in ids:
                ids[v] = len(ids) + 1
                o.write("v %r %r %r\n" % tuple(pos[v]))
        out.append(t)
    for t in out: o.write("f %d %d %d\n" % tuple(ids[v] for v in t))
EOF

printf "%-22s %-5s %6s %6s %6s %7s %7s %6s %10s %10s %8s %8s %8s %10s %10s\n" mesh holes in out filled n_o n_r \
  n_r/n_o rms max bytes cpu_s rss_mb bd_rms bd_max
for spec in "terrain:$work/terrain.obj" "spot_cut:$work/spot_cut.obj" "bunny_zipper:$shared/bunny_zipper.ply" \
            "elephant-with-holes:$cgal/elephant-with-holes.off" "mech-holes-shark:$cgal/mech-holes-shark.off"; do
  name="${spec%%:*}"
  file="${spec#*:}"
  if [ -n "$only" ] && ! echo " $only " | grep -q " $name "; then continue; fi
  for mode in open fill prm thin; do
    flag=""
    [ "$mode" = fill ] && flag="--fill-holes"
    [ "$mode" = prm ] && flag="--mode prm"
    [ "$mode" = thin ] && flag="--mode prm --boundary-simplification 1"
    if ! /usr/bin/time -f '%U %S %M' -o "$work/time" "$prm" pack "$file" --target-error "$target" $flag --json \
         -o "$work/out.prm" > "$work/report.json" 2> "$work/err"; then
      printf "%-22s %-5s failed: %s\n" "$name" "$mode" "$(grep -v '^{' "$work/err" | tail -1)"
      continue
    fi
    bd="- -"
    [ "$mode" != fill ] && bd="$("$distance" "$file" "$work/out.prm" | sed 's/.*RMS \([^ ]*\) max \([^ ]*\) .*/\1 \2/')"
    python3 - "$name" "$mode" "$work/report.json" "$work/time" $bd <<'EOF'
import json, sys
name, mode, report, timef, bd_rms, bd_max = sys.argv[1:7]
r = json.load(open(report))
u, s, m = open(timef).read().split()[:3]
print("%-22s %-5s %6d %6d %6d %7d %7d %6.3f %10.3e %10.3e %8d %8.2f %8.0f %10s %10s" % (
    name, mode, r["boundary_loops_in"], r["boundary_loops_out"], r["holes_closed"], r["n_o"], r["n_r"],
    r["n_r"] / r["n_o"], r["distance"]["rms_rel"], r["distance"]["max_rel"], r["bytes"]["total"],
    float(u) + float(s), int(m) / 1024, bd_rms, bd_max))
EOF
  done
done
