#!/usr/bin/env bash
# Issue 22 "never worse than not remeshing" (bench/README.md, "pack --mode"): `prm pack MESH --target-error E` (mode
# auto, default effort) over meshes given on the command line (default: every mesh of ../shared/meshes): the mode
# auto chose, both candidates' bytes (the piecewise regular stream and the input coded through the general path),
# n_o, n_r, n_r/n_o, the RMS and maximum distance of the decoded mesh to the input, and the CPU seconds of the whole
# pack (user + system, /usr/bin/time). One markdown row per mesh on stdout.
#
#   bench/pack_mode_table.sh [--prm PRM_BINARY] [--target E] [MESH ...]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
prm="$root/build/tools/prm/prm"
target="2e-4"
files=()
while [ $# -gt 0 ]; do
  case "$1" in
    --prm) prm="$2"; shift 2 ;;
    --target) target="$2"; shift 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
if [ ${#files[@]} -eq 0 ]; then
  meshes="$(cd "$root/.." && pwd)/shared/meshes"
  files=("$meshes"/*.ply "$meshes"/*.off "$meshes"/*.obj)
fi
[ -x "$prm" ] || { echo "pack_mode_table: $prm is not built" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "| mesh | mode | PRM bytes | general bytes (bits) | n_o | n_r | n_r/n_o | RMS | max | CPU s |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for f in "${files[@]}"; do
  name=$(basename "$f")
  echo "pack_mode_table: $name at $target" >&2
  if /usr/bin/time -f '%U %S' -o "$work/time.txt" "$prm" pack "$f" -o "$work/out.prm" --target-error "$target" --json \
      > "$work/r.json" 2> "$work/err.txt"; then
    python3 - "$name" "$work/r.json" "$work/time.txt" <<'PY'
import json, sys
d = json.load(open(sys.argv[2]))
user, system = (float(x) for x in open(sys.argv[3]).read().split()[-2:])
c = d["candidates"]
def prm(c):
    return f'{c["bytes"]:,}' if c["made"] else ("refused: " + c.get("refused", "")[:80] if c.get("refused") else "-")
def gen(c):
    return f'{c["bytes"]:,} ({c["bits"]})' if c["made"] else ("refused: " + c.get("refused", "")[:80] if c.get("refused") else "-")
print(f'| {sys.argv[1]} | {d["mode"]} | {prm(c["prm"])} | {gen(c["general"])} | {d["n_o"]:,} | {d["n_r"]:,} | '
      f'{d["n_r_over_n_o"]:.3f} | {d["distance"]["rms_rel"]:.3e} | {d["distance"]["max_rel"]:.3e} | {user + system:.1f} |')
PY
  else
    echo "| $name | failed (exit $?): $(tail -c 160 "$work/err.txt" | tr '\n|' '  ') | | | | | | | | |"
  fi
done
