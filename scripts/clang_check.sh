#!/usr/bin/env bash
# Every source file of a configured build compiled by clang as well, syntax and semantics only (no code is made):
# the build is GCC's, and GCC accepts some C++20 in -std=c++17 code (e.g. a lambda capturing a structured binding)
# that clang refuses. Run after scripts/test.sh (it reads build/compile_commands.json), as CI does.
#   scripts/clang_check.sh [BUILD_DIR]      default build/
# Exit 0: every file compiles; 1: a file does not (clang's errors are printed); 2: no compile_commands.json or clang.
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in -h|--help) sed -n '2,6p' "$0"; exit 0 ;; esac
build=${1:-build}
db="$build/compile_commands.json"
[ -f "$db" ] || { echo "clang_check: no $db (configure the build first)" >&2; exit 2; }
command -v clang++ > /dev/null || { echo "clang_check: clang++ is not installed (scripts/setup.sh installs it)" >&2; exit 2; }

# One command per translation unit of the repository (not fetched or generated sources): GCC's flags, GCC's
# driver replaced by clang's, no output file, warnings off (GCC's warning options differ).
list=$(mktemp)
trap 'rm -f "$list"' EXIT
python3 - "$db" "$PWD" > "$list" <<'EOF'
import json, shlex, sys
db, root = sys.argv[1], sys.argv[2]
seen = set()
for e in json.load(open(db)):
    f = e['file']
    if f in seen or not f.startswith(root + '/') or '/_deps/' in f or not f.endswith(('.cpp', '.cc', '.c')):
        continue
    seen.add(f)
    args = e.get('arguments') or shlex.split(e['command'])
    out, skip = [], False
    for a in args[1:]:
        if skip:
            skip = False
        elif a in ('-o', '-MF', '-MT', '-MQ'):
            skip = True
        elif a != '-c' and not a.startswith('-MD') and a != f and not a.endswith(('ccache', 'g++', 'gcc', 'c++', 'cc')):
            out.append(a)
    driver = 'clang' if f.endswith('.c') else 'clang++'
    print(shlex.join(['cd', e['directory']]) + ' && ' + shlex.join([driver, '-fsyntax-only', '-w', *out, f]))
EOF
count=$(wc -l < "$list")
failed=0
# xargs runs them two at a time; a failing file prints clang's errors and makes the run fail.
if ! xargs -d '\n' -n 1 -P "$(nproc)" bash -c 'eval "$1"' clang_check < "$list"; then failed=1; fi
if [ "$failed" -ne 0 ]; then
  echo "clang_check: clang refuses a source file above ($count files checked)" >&2
  exit 1
fi
echo "clang_check: $count files compile with clang ($(clang++ --version | head -1))"
