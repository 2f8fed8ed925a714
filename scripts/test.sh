#!/usr/bin/env bash
# Sets up (Debian packages), builds and runs the whole test suite.
#   scripts/test.sh                 Release build in build/, all tests
#   scripts/test.sh --sanitize      ASan+UBSan build in build-asan/ (tests labelled 'heavy' are skipped there:
#                                   the same code paths run on smaller inputs)
set -euo pipefail
cd "$(dirname "$0")/.."

sanitize=0
for arg in "$@"; do
  case "$arg" in
    --sanitize) sanitize=1 ;;
    -h|--help) sed -n '2,6p' "$0"; exit 0 ;;
    *) echo "test.sh: unknown argument '$arg'" >&2; exit 1 ;;
  esac
done

bash scripts/setup.sh
jobs=$(nproc)
if [ "$sanitize" -eq 1 ]; then
  cc=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DPRM_SANITIZE=address,undefined -DPRM_BUILD_BENCH=OFF)
  dir=build-asan
  exclude=(-LE heavy)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
else
  cc=(-DCMAKE_BUILD_TYPE=Release)
  dir=build
  exclude=()
fi
cmake -S . -B "$dir" -G Ninja "${cc[@]}"
cmake --build "$dir" -j "$jobs"
ctest --test-dir "$dir" --output-on-failure -j "$jobs" "${exclude[@]}"
