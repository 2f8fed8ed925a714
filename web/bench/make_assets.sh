#!/usr/bin/env bash
# web/bench/make_assets.sh PRM OUT_DIR MESH...: each mesh (OBJ or PLY: draco_encoder reads no OFF) packed by
# `prm pack` ($PACK_ARGS, default --grid-fraction 0.01; e.g. PACK_ARGS='--target-error 2e-4' lets --mode auto choose) and by Draco's draco_encoder (-cl 7) at matched error: the smallest -qp in 6..16 whose symmetric RMS distance to the input
# (`prm compare`) is at most the PRM stream's. Writes OUT_DIR/NAME.prm, NAME.drc and assets.json.
set -euo pipefail
prm="$1"; out="$2"; shift 2
read -r -a pack_args <<< "${PACK_ARGS:---grid-fraction 0.01}"
mkdir -p "$out"
rms() { "$prm" compare --json "$1" "$2" 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["symmetric"]["rms_rel"])'; }
entries=()
for mesh in "$@"; do
  name="$(basename "${mesh%.*}")"
  "$prm" pack "$mesh" -o "$out/$name.prm" "${pack_args[@]}" >/dev/null
  "$prm" decode "$out/$name.prm" -o "$out/$name.prm.ply" --double >/dev/null
  prm_rms=$(rms "$mesh" "$out/$name.prm.ply")
  lo=6; hi=16  # bisection: Draco's RMS falls as -qp grows
  while [ $lo -lt $hi ]; do
    mid=$(( (lo + hi) / 2 ))
    draco_encoder -i "$mesh" -o "$out/$name.drc" -qp $mid -cl 7 >/dev/null
    draco_decoder -i "$out/$name.drc" -o "$out/$name.drc.ply" >/dev/null
    if python3 -c "import sys; sys.exit(0 if $(rms "$mesh" "$out/$name.drc.ply") <= $prm_rms else 1)"; then hi=$mid; else lo=$((mid + 1)); fi
  done
  draco_encoder -i "$mesh" -o "$out/$name.drc" -qp $lo -cl 7 >/dev/null
  draco_decoder -i "$out/$name.drc" -o "$out/$name.drc.ply" >/dev/null
  drc_rms=$(rms "$mesh" "$out/$name.drc.ply")
  entries+=("{\"name\": \"$name\", \"prm\": \"$name.prm\", \"drc\": \"$name.drc\", \"prm_rms\": $prm_rms, \"draco_qp\": $lo, \"drc_rms\": $drc_rms}")
  echo "$name: PRM RMS $prm_rms, Draco -qp $lo RMS $drc_rms" >&2
done
(IFS=,; echo "[${entries[*]}]") > "$out/assets.json"
