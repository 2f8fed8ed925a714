#!/usr/bin/env bash
# The scale bench (issue 21, bench/README.md "Scale"): CPU seconds and peak memory of `prm remesh` at a fixed grid,
# `prm pack --target-error 2e-4` (default effort) and Draco's encoder (-qp 11 -cl 10) on meshes of growing size.
# One tab-separated row per run on stdout (append them to a file; bench/scale_plot.sh and scale_rows.py read it):
#   mesh  V  tool  cpu_s  peak_kb  exit  output_bytes  output_vertices
#
#   bench/scale_table.sh PRM_BINARY WORK_DIR [--tools "remesh pack draco"] [--grid 0.00114 --bits 11] MESH...
#
# Each run is `/usr/bin/time -f '%U %S %M'` (user + system CPU seconds, peak resident KB). Outputs go to WORK_DIR.
set -euo pipefail
prm="$1"
work="$2"
shift 2
tools="remesh pack draco"
grid=0.00114
bits=11
target=2e-4
meshes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --tools) tools="$2"; shift 2 ;;
    --grid) grid="$2"; shift 2 ;;
    --bits) bits="$2"; shift 2 ;;
    --target-error) target="$2"; shift 2 ;;
    *) meshes+=("$1"); shift ;;
  esac
done
[ -x "$prm" ] || { echo "scale_table: $prm is not built" >&2; exit 2; }
mkdir -p "$work"

json_field() {  # json_field FILE KEY: a top-level number of a --json report, empty if absent
  python3 -c 'import json,sys
try: print(json.load(open(sys.argv[1])).get(sys.argv[2], ""))
except Exception: print("")' "$1" "$2"
}

for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh")
  stem="$work/${name%.*}"
  v=$("$prm" info "$mesh" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["vertices"])')
  for tool in $tools; do
    echo "scale_table: $tool $name ($v vertices)" >&2
    set +e
    case "$tool" in
      remesh)
        /usr/bin/time -f '%U %S %M' -o "$stem.remesh.time" "$prm" remesh "$mesh" --grid "$grid" --bits "$bits" \
          -o "$stem.remesh.ply" --json > "$stem.remesh.json" 2> "$stem.remesh.err"
        code=$?; out="$stem.remesh.ply"; outv=$(json_field "$stem.remesh.json" vertices) ;;
      pack)
        /usr/bin/time -f '%U %S %M' -o "$stem.pack.time" "$prm" pack "$mesh" --target-error "$target" \
          -o "$stem.prm" --json > "$stem.pack.json" 2> "$stem.pack.err"
        code=$?; out="$stem.prm"; outv=$(json_field "$stem.pack.json" vertices) ;;
      draco)
        /usr/bin/time -f '%U %S %M' -o "$stem.draco.time" draco_encoder -i "$mesh" -o "$stem.drc" -qp 11 -cl 10 \
          > "$stem.draco.out" 2> "$stem.draco.err"
        code=$?; out="$stem.drc"; outv=$v ;;
      *) echo "scale_table: unknown tool $tool" >&2; exit 1 ;;
    esac
    set -e
    read -r user sys peak < <(tail -1 "$stem.$tool.time")
    bytes=$([ -f "$out" ] && [ "$code" = 0 ] && stat -c %s "$out" || echo "")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$v" "$tool" "$(awk "BEGIN { printf \"%.2f\", $user + $sys }")" \
      "$peak" "$code" "$bytes" "$outv"
  done
done
