#!/usr/bin/env bash
# The codec as a library, as a user gets it (README "Using the library"):
#   1. configured alone (PRM_CODEC_ONLY: no package but a compiler and CMake; GoogleTest hidden) in a clean build
#      directory, shared libraries, warnings as errors; its C API test run;
#   2. the decoder library checked for encoder code (no global function of the encoder's objects in it);
#   3. installed, and examples/ built against the installed tree with find_package(prm) and with pkg-config, then
#      run on a conformance vector and checked against its recorded counts.
# Usage: scripts/package_test.sh [--static] [BUILD_DIR]   (default build-codec-only; removed first)
#   --static: static libraries instead (the encoder check then reads libprm_decoder.a)
set -euo pipefail
cd "$(dirname "$0")/.."
shared=ON
if [ "${1:-}" = "--static" ]; then shared=OFF; shift; fi
dir=$(realpath -m "${1:-build-codec-only}")
prefix=$dir/install
rm -rf "$dir"
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPRM_CODEC_ONLY=ON -DBUILD_SHARED_LIBS=$shared -DPRM_WERROR=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON
cmake --build "$dir" -j "$(nproc)"
ctest --test-dir "$dir" --output-on-failure

# 2. The decoder alone: none of the encoder's global functions.
enc=$(nm --defined-only "$dir"/codec/CMakeFiles/prm_encoder_objects.dir/src/*.o | awk '$2 == "T" {print $3}' | sort -u)
declib="$dir/codec/libprm_decoder.so"
[ "$shared" = ON ] || declib="$dir/codec/libprm_decoder.a"
dec=$(nm --defined-only "$declib" | awk 'NF == 3 {print $3}' | sort -u)
both=$(comm -12 <(echo "$enc") <(echo "$dec"))
if [ -z "$enc" ] || [ -z "$dec" ]; then
  echo "package_test: no symbols read from the encoder objects or $declib" >&2
  exit 1
fi
if [ -n "$both" ]; then
  echo "package_test: libprm_decoder holds encoder functions:" >&2
  echo "$both" | c++filt >&2
  exit 1
fi
echo "package_test: libprm_decoder holds none of the encoder's $(echo "$enc" | wc -l) global functions"

# 3. Installed, and used from a separate project.
cmake --install "$dir" --prefix "$prefix"
(cd "$prefix" && find . -type f -o -type l | sort)
cmake -S examples -B "$dir/examples" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_COMPILE_WARNING_AS_ERROR=ON
cmake --build "$dir/examples"
libdir=$(dirname "$(find "$prefix" -name 'libprm_decoder.*' | head -1)")
export PKG_CONFIG_PATH="$libdir/pkgconfig"
# shellcheck disable=SC2046
cc -std=c99 -Wall -Wextra -pedantic -Werror examples/decode_arrays.c -o "$dir/decode_arrays_pkgconfig" \
  $(pkg-config --static --cflags --libs prm-decoder) -Wl,-rpath,"$libdir"
vector=conformance/vectors/013-prm-1.2-prediction
want="$(sed -n 's/.*"vertices": \([0-9]*\).*/\1/p' $vector/vector.json) vertices, $(sed -n 's/.*"triangles": \([0-9]*\).*/\1/p' $vector/vector.json) triangles"
cxx=$("$dir/examples/decode_arrays" $vector/stream.prm)
c=$("$dir/examples/decode_arrays_c" $vector/stream.prm)
pc=$("$dir/decode_arrays_pkgconfig" $vector/stream.prm)
echo "$cxx"
if [[ "$cxx" != *"$want"* ]] || [ "$c" != "$cxx" ] || [ "$pc" != "$cxx" ]; then
  echo "package_test: the examples disagree or miss '$want':" >&2
  printf '  C++: %s\n  C: %s\n  pkg-config: %s\n' "$cxx" "$c" "$pc" >&2
  exit 1
fi
if "$dir/examples/decode_arrays" conformance/invalid/101-crc/stream.prm 2>/dev/null; then
  echo "package_test: a stream with a bad CRC decoded" >&2
  exit 1
fi
echo "package_test: ok"
