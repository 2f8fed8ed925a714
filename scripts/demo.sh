#!/usr/bin/env bash
# The main job on a real mesh: install what is missing, build, then repair + remesh + encode + decode + report,
# next to Draco; it ends by writing the stream into a .glb and validating it. Usage: scripts/demo.sh [MESH] [TARGET_RMS_ERROR]
#   MESH defaults to ../shared/meshes/horse.ply (the paper's horse), or CGAL's bunny00 when ../shared is absent.
#   TARGET_RMS_ERROR is a fraction of the bounding-box diagonal (default 2e-4, the paper's regime).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target prm
prm=build/tools/prm/prm

mesh=${1:-}
if [ -z "$mesh" ]; then
  if [ -f ../shared/meshes/horse.ply ]; then mesh=../shared/meshes/horse.ply
  else mesh=build/cgal-data/data/meshes/bunny00.off; fi
fi
target=${2:-2e-4}
out=build/demo
mkdir -p "$out"
name=$(basename "${mesh%.*}")

echo
echo "== 1. the input: $mesh"
$prm info "$mesh"

if $prm --help | grep -q ' pack'; then
  echo
  echo "== 2. pack: repair, remesh to RMS error <= $target of the diagonal, encode"
  $prm pack "$mesh" -o "$out/$name.prm" --target-error "$target"
  echo
  echo "== 3. unpack: decode the stream"
  $prm unpack "$out/$name.prm" -o "$out/$name.decoded.ply" --double  # the dequantized positions exactly
else
  echo
  echo "== 2. remesh to RMS error <= $target of the diagonal (paper §2)"
  $prm remesh "$mesh" -o "$out/$name.prm.ply" --target-error "$target"
  echo
  echo "== 3. encode the piecewise regular mesh, then decode it"
  $prm encode "$out/$name.prm.ply" -o "$out/$name.prm"
  $prm decode "$out/$name.prm" -o "$out/$name.decoded.ply" --double
fi
echo
echo "== 4. the decoded mesh against the original (Metro-style distances)"
$prm compare "$mesh" "$out/$name.decoded.ply"

echo
echo "== 5. against Draco (edgebreaker, compression level 10) on the original: 12-bit positions, and at matched error"
if command -v draco_encoder >/dev/null; then
  draco_encoder -i "$mesh" -o "$out/$name.drc" -qp 12 -cl 10 -qt -1 -qn -1 -qg -1 >/dev/null
  ours=$(stat -c %s "$out/$name.prm")
  theirs=$(stat -c %s "$out/$name.drc")
  echo "  PRM stream:   $ours bytes"
  echo "  Draco stream: $theirs bytes  (PRM is $(awk "BEGIN{printf \"%.2f\", $ours/$theirs}") of Draco)"
  # At matched error: the smallest -qp (6..16) whose decoded RMS distance to the original is at most PRM's.
  if command -v draco_decoder >/dev/null; then
    rms() { $prm compare --json "$mesh" "$1" | python3 -c 'import json,sys; print(json.load(sys.stdin)["symmetric"]["rms_rel"])'; }
    draco_at() {
      draco_encoder -i "$mesh" -o "$out/$name.qp.drc" -qp "$1" -cl 10 -qt -1 -qn -1 -qg -1 >/dev/null
      draco_decoder -i "$out/$name.qp.drc" -o "$out/$name.qp.ply" >/dev/null
    }
    ours_rms=$(rms "$out/$name.decoded.ply")
    lo=6; hi=16
    while [ $lo -lt $hi ]; do
      mid=$(( (lo + hi) / 2 ))
      draco_at $mid
      if python3 -c "import sys; sys.exit(0 if $(rms "$out/$name.qp.ply") <= $ours_rms else 1)"; then hi=$mid; else lo=$((mid + 1)); fi
    done
    draco_at $lo
    matched=$(stat -c %s "$out/$name.qp.drc")
    echo "  at matched error (RMS $ours_rms of the diagonal): Draco -qp $lo, RMS $(rms "$out/$name.qp.ply"), $matched bytes  (PRM is $(awk "BEGIN{printf \"%.2f\", $ours/$matched}") of Draco)"
  fi
fi
echo
echo "== 6. the stream as a compressed glTF (PRM_mesh_compression), checked by the Khronos glTF-Validator"
$prm pack "$out/$name.prm" -o "$out/$name.glb"
node tools/gltf_validator/validate.js "$out/$name.glb"
echo
echo "Outputs in $root/$out/"
