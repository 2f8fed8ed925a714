#!/usr/bin/env bash
# The libraries of a full build as a user gets them (README "Using the library", issue 18 item 3): a build that is
# configured and built already (scripts/test.sh's Release build/, static libraries; or another one, e.g. with
# -DBUILD_SHARED_LIBS=ON) installed into a temporary prefix, then
#   1. every installed header compiled alone, and none including a private dependency's header;
#   2. examples/ (the decoder) built against it with find_package(prm): no other package is looked for;
#   3. examples/pack_glb built with find_package(prm COMPONENTS gltf) and run on ../shared/meshes/spot.obj; the .glb
#      it writes read back by the installed `prm` tool. With shared libraries, the private dependencies (Draco,
#      OpenMesh...) must not have been looked for either.
# Usage: scripts/package_test_full.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(realpath "${1:-build}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/install
fail() { echo "package_test_full: $*" >&2; exit 1; }

cmake --install "$dir" --prefix "$prefix" > /dev/null
(cd "$prefix" && find . -type f -o -type l | sort)

# 1. Headers: self-contained, and the private dependencies stay private.
if grep -rEn '#include [<"](OpenMesh|tiny_gltf|tbb|oneapi|draco|meshoptimizer|tiny_obj_loader)' "$prefix/include"; then
  fail "an installed header includes a private dependency"
fi
headers=$(cd "$prefix/include" && find . -name '*.h' | sed 's|^\./||' | sort)
for h in $headers; do
  echo "#include \"$h\"" | c++ -std=c++17 -fsyntax-only -Wall -Wextra -Werror -I"$prefix/include" -x c++ - ||
    fail "$h does not compile on its own"
done
echo "package_test_full: $(echo "$headers" | wc -l) installed headers compile on their own"

# 2. find_package(prm) alone: the codec, nothing else.
cmake -S examples -B "$work/examples" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_COMPILE_WARNING_AS_ERROR=ON > /dev/null
cmake --build "$work/examples" > /dev/null
deps='^(Threads|TBB|OpenMesh|draco|meshoptimizer|tinyobjloader|nlohmann_json)_DIR:'
if grep -E "$deps" "$work/examples/CMakeCache.txt"; then fail "find_package(prm) looked for other packages"; fi
"$work/examples/decode_arrays" conformance/vectors/013-prm-1.2-prediction/stream.prm

# 3. find_package(prm COMPONENTS gltf): a mesh packed into a .glb and decoded again.
cmake -S examples/pack_glb -B "$work/pack_glb" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_COMPILE_WARNING_AS_ERROR=ON > /dev/null
cmake --build "$work/pack_glb" > /dev/null
echo "package_test_full: pack_glb found $(grep -E "$deps" "$work/pack_glb/CMakeCache.txt" | sed 's/_DIR:.*//' | xargs)"
if [ -n "$(find "$prefix" -name 'libprm_gltf.so*' -print -quit)" ] &&
   grep -E '^(OpenMesh|draco|meshoptimizer|tinyobjloader)_DIR:' "$work/pack_glb/CMakeCache.txt"; then
  fail "shared libraries, yet find_package(prm COMPONENTS gltf) looked for their private dependencies"
fi
packed=$("$work/pack_glb/pack_glb" ../shared/meshes/spot.obj "$work/spot.glb" 0.02)
echo "$packed"
counts=$(echo "$packed" | sed -n 's/.*decodes to \([0-9]* vertices, [0-9]* triangles\).*/\1/p')
info=$("$prefix/bin/prm" info "$work/spot.glb")
echo "$info"
[ -n "$counts" ] && [[ "$info" == *"$counts"* ]] || fail "the installed prm tool does not read '$counts' from the .glb"
echo "package_test_full: ok"
