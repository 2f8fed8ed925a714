#!/bin/sh
# Sums codec/fuzz/run.sh's log per target and build: executions, seconds, executions per second, findings.
#   codec/fuzz/totals.sh [LOG]      (default build-fuzz/fuzz-log.tsv)
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
log=${1:-$root/build-fuzz/fuzz-log.tsv}
[ -f "$log" ] || { echo "totals.sh: no log at $log" >&2; exit 2; }
printf '| target | build | executions | seconds | exec/s | runs with a finding |\n|---|---|---:|---:|---:|---:|\n'
awk -F '\t' '
  { key = $4 " " $3; n[key] += $5; s[key] += $6; if ($8 != "none") f[key]++ }
  END {
    for (k in n) {
      split(k, p, " ")
      printf "| %s | %s | %d | %d | %.0f | %d |\n", p[1], p[2], n[k], s[k], s[k] ? n[k] / s[k] : 0, f[k]
    }
  }' "$log" | sort
