#!/usr/bin/env bash
# web/run_tests.sh build WORK_DIR | conformance | size | browser PRM MAKE_SCENE WORK_DIR: the steps of the web ctests
# (web/CMakeLists.txt).
# Exit 77 (ctest: skipped) with a message when emcc, or for the browser test chromium or npm's packages, is absent.
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
export NODE_PATH="${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs"
if ! command -v emcc >/dev/null; then
  echo "SKIPPED: emcc not found; scripts/setup.sh installs Debian's emscripten" >&2
  exit 77
fi
case "${1:-}" in
  build) exec "$web/build.sh" "$2" ;;
  conformance) exec node --test "$web/test/conformance.test.js" ;;
  size)
    # Issue 20: the gzipped module under half of Draco's draco_decoder.wasm as npm three 0.187.0 ships it (88,200 B
    # with gzip -9), measured as web/README.md does.
    limit=44100
    bytes="$(gzip -9 -c "$web/dist/prm_decoder_wasm.wasm" | wc -c)"
    if [ "$bytes" -ge "$limit" ]; then
      echo "FAIL: web/dist/prm_decoder_wasm.wasm is $bytes B with gzip -9, the limit is under $limit B" >&2
      exit 1
    fi
    echo "ok: web/dist/prm_decoder_wasm.wasm is $bytes B with gzip -9 (under $limit B)" ;;
  browser)
    if [ ! -x /usr/bin/chromium ] || [ ! -d "$web/node_modules/puppeteer-core" ] || [ ! -d "$web/node_modules/three" ]; then
      echo "SKIPPED: /usr/bin/chromium or web/node_modules missing; scripts/setup.sh installs them" >&2
      exit 77
    fi
    PRM="$2" MAKE_SCENE="$3" WORK="$4" exec node --test "$web/test/browser.test.js" ;;
  *) echo "usage: web/run_tests.sh build WORK_DIR | conformance | size | browser PRM MAKE_SCENE WORK_DIR" >&2; exit 1 ;;
esac
