#!/usr/bin/env bash
# `prm info` and `prm compare` on every mesh of ../shared/meshes and of CGAL's data/meshes (issue 2's "done
# when"). Each file is read and validated (exit 0) or refused with a clear message (exit 2); a crash (exit >= 128)
# or any other code is a failure. Each mesh that reads is then compared with what `prm encode` + `prm decode`
# (12-bit positions) make of it, or with itself where the codec refuses it (non-manifold input): the symmetric RMS
# (fraction of the diagonal) is listed, and a mesh against itself must give 0 (below 1e-12).
# Usage: bench/every_mesh.sh PRM_BINARY [CGAL_MESH_DIR]      (prints one line per mesh, then a summary)
set -uo pipefail
prm=${1:?usage: every_mesh.sh PRM_BINARY [CGAL_MESH_DIR]}
here=$(cd "$(dirname "$0")/.." && pwd)
cgal=${2:-$(dirname "$prm")/../../cgal-data/data/meshes}
shared="$here/../shared/meshes"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

read_ok=0 refused=0 failed=0 compared=0 self=0 cmp_failed=0
start=$(date +%s)
printf '%-40s %-8s %10s %10s  %s\n' mesh info vertices "RMS/diag" "compared with"
for f in "$shared"/*.{ply,obj,off,stl,glb,gltf} "$cgal"/*.{ply,obj,off,stl,glb,gltf}; do
  [ -e "$f" ] || continue
  name=$(basename "$f")
  "$prm" info "$f" --json > "$tmp/info.json" 2> "$tmp/err"
  rc=$?
  if [ $rc -eq 2 ]; then
    refused=$((refused + 1))
    printf '%-40s %-8s %s\n' "$name" refused "$(tr '\n' ' ' < "$tmp/err" | head -c 120)"
    continue
  elif [ $rc -ne 0 ]; then
    failed=$((failed + 1))
    printf '%-40s FAILED (exit %d)\n' "$name" "$rc"
    continue
  fi
  read_ok=$((read_ok + 1))
  verts=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["vertices"])' "$tmp/info.json")
  other="$f" with=itself
  if "$prm" encode "$f" -o "$tmp/m.prm" > /dev/null 2>&1 && "$prm" decode "$tmp/m.prm" -o "$tmp/m.ply" --double > /dev/null 2>&1; then
    other="$tmp/m.ply" with="12-bit decode"
  fi
  if "$prm" compare "$f" "$other" --json > "$tmp/cmp.json" 2> "$tmp/err"; then
    rms=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print("%.3e" % d["symmetric"]["rms_rel"])' "$tmp/cmp.json" 2>/dev/null || echo "?")
    compared=$((compared + 1))
    if [ "$with" = itself ]; then
      self=$((self + 1))
      python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) < 1e-12 else 1)' "$rms" ||
        { cmp_failed=$((cmp_failed + 1)); with="itself: NOT ZERO"; }
    fi
    printf '%-40s %-8s %10s %10s  %s\n' "$name" ok "$verts" "$rms" "$with"
  else
    cmp_failed=$((cmp_failed + 1))
    printf '%-40s %-8s %10s compare FAILED: %s\n' "$name" ok "$verts" "$(tr '\n' ' ' < "$tmp/err" | head -c 120)"
  fi
done
echo "info: $read_ok read, $refused refused with a message, $failed failed"
echo "compare: $compared compared ($self with themselves), $cmp_failed failed"
echo "time: $(( $(date +%s) - start )) s"
[ $failed -eq 0 ] && [ $cmp_failed -eq 0 ]
