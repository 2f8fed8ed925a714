// PRM_ALWAYS_INLINE: a function the decoder's hot loops call, to be inlined whatever the compiler's heuristics say.
// PRM_WASM_INLINE (PRM_WASM_INLINE_LAMBDA after a lambda's parameters): the same for the WebAssembly build only
// (web/build.sh). Clang left these as calls there, one per decoded value, corner or neighbour: with them forced in,
// hdecode's wasm decodes 11-13% faster than before it, without them 0-2% (web/README.md). GCC inlines what pays
// natively, and forcing the same functions there cost instructions (callgrind: +5% on a venus stream), so the native
// build keeps its own choices.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define PRM_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define PRM_ALWAYS_INLINE inline
#endif

#if defined(__wasm__)
#define PRM_WASM_INLINE inline __attribute__((always_inline))
#define PRM_WASM_INLINE_LAMBDA __attribute__((always_inline))
#else
#define PRM_WASM_INLINE inline
#define PRM_WASM_INLINE_LAMBDA
#endif
