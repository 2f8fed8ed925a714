#!/usr/bin/env bash
# File size of `prm pack` (PRM_mesh_compression) against draco_transcoder (KHR_draco_mesh_compression) and
# gltfpack -cc (EXT_meshopt_compression + KHR_mesh_quantization) on three scenes built from ../shared/meshes, at
# matched RMS error. Usage: bench/gltf/scene_sizes.sh [TARGET_ERROR] (default 5e-4), from the repository root, after
# a build in build/ (prm, prm_gltf_make_scene) and `npm ci` in bench/gltf.
#
# How the error is matched: every output is decoded into a plain glTF by `prm unpack` (PRM, Draco and meshopt are
# all decoded by their own decoders; quantized positions are read as KHR_mesh_quantization says) and measured
# against the input scene by `prm compare` (Metro-style symmetric RMS over the whole scene in world space, as a
# fraction of the scene's bounding-box diagonal). PRM is packed at TARGET_ERROR per primitive; for Draco
# (-qp 6..16) and gltfpack (-vp 6..16) the coarsest position quantization whose scene RMS is at most PRM's is taken.
# Normals: the inputs have them; Draco and gltfpack store them (their default bits), PRM regenerates them.
set -euo pipefail
target=${1:-5e-4}
prm=build/tools/prm/prm
make_scene=build/gltf_ext/prm_gltf_make_scene
gltfpack=bench/gltf/node_modules/.bin/gltfpack
meshes=../shared/meshes
out=build/bench_gltf
mkdir -p "$out"

rms_of() {  # rms_rel of the decoded $1 against the scene $2
  $prm unpack "$1" -o "$out/_plain.glb" >/dev/null
  $prm compare --json "$2" "$out/_plain.glb" | python3 -c 'import json,sys; print(json.load(sys.stdin)["symmetric"]["rms_rel"])'
}

printf '| scene | input | PRM (RMS) | Draco (-qp, RMS) | gltfpack -cc (-vp, RMS) |\n|---|---:|---:|---:|---:|\n'
for scene in "animals:spot.obj rabbit_1k_decimated.off" "cad:fandisk.obj rocker-arm.off" "cats:feline_5k.obj spot.obj"; do
  name=${scene%%:*}
  files=()
  for f in ${scene#*:}; do files+=("$meshes/$f"); done
  s="$out/$name.glb"
  $make_scene "$s" --meshes "${files[@]}"
  $prm pack "$s" -o "$out/$name.prm.glb" --target-error "$target" >/dev/null
  prm_rms=$(rms_of "$out/$name.prm.glb" "$s")
  prm_size=$(stat -c %s "$out/$name.prm.glb")
  draco="none"
  for qp in 6 7 8 9 10 11 12 13 14 15 16; do
    draco_transcoder -i "$s" -o "$out/$name.draco.glb" -qp $qp >/dev/null
    r=$(rms_of "$out/$name.draco.glb" "$s")
    if python3 -c "import sys; sys.exit(0 if $r <= $prm_rms else 1)"; then
      draco="$(stat -c %s "$out/$name.draco.glb") ($qp, $(printf %.2e "$r"))"
      break
    fi
  done
  gp="none"
  for vp in 6 7 8 9 10 11 12 13 14 15 16; do
    $gltfpack -i "$s" -o "$out/$name.gltfpack.glb" -cc -vp $vp >/dev/null
    r=$(rms_of "$out/$name.gltfpack.glb" "$s")
    if python3 -c "import sys; sys.exit(0 if $r <= $prm_rms else 1)"; then
      gp="$(stat -c %s "$out/$name.gltfpack.glb") ($vp, $(printf %.2e "$r"))"
      break
    fi
  done
  printf '| %s (%s) | %s | %s (%.2e) | %s | %s |\n' "$name" "${scene#*:}" "$(stat -c %s "$s")" "$prm_size" "$prm_rms" "$draco" "$gp"
done
