#!/bin/sh
# The worst-case error of `prm pack` (issue 22 item 3, bench/README.md "Worst-case error"): per mesh, the decoded
# stream's RMS and max (sampled Hausdorff) error, its bytes and the CPU seconds, without the local refinement
# (the default, as before issue 22), with it (--local-refinement), and with --max-error M.
# Usage: bench/max_error_table.sh PRM TARGET MAX_ERROR MESH...   (prints one Markdown row per mesh and mode)
set -eu
prm=$1; target=$2; max=$3; shift 3
out=$(mktemp -d)
echo "| mesh | mode | bytes | RMS | max | max/target | refined vertices | CPU s |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for mesh in "$@"; do
  name=$(basename "$mesh")
  for mode in default refined max; do
    case $mode in
      default) extra="" ;;
      refined) extra="--local-refinement" ;;
      max) extra="--max-error $max" ;;
    esac
    # shellcheck disable=SC2086
    if /usr/bin/time -f '%U %S' -o "$out/time" "$prm" pack "$mesh" --target-error "$target" $extra \
        -o "$out/s.prm" --json > "$out/j.json" 2> "$out/err"; then
      python3 - "$out/j.json" "$out/time" "$name" "$mode" "$target" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
u, s = (float(x) for x in open(sys.argv[2]).read().split()[-2:])
t = float(sys.argv[5])
print(f"| {sys.argv[3]} | {sys.argv[4]} | {d['bytes']['total']} | {d['distance']['rms_rel']:.3e} | "
      f"{d['distance']['max_rel']:.3e} | {d['distance']['max_rel'] / t:.1f} | {d.get('refined_vertices', 0)} | {u + s:.1f} |")
PY
    else
      echo "| $name | $mode | failed: $(tail -c 200 "$out/err" | tr '\n' ' ') | | | | | |"
    fi
  done
done
rm -rf "$out"
