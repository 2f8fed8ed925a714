// Bench-only hooks for the entropy-layer study (bench/entropy_study/, bench/README.md "hdecode8"), compiled to nothing
// unless PRM_ENTROPY_TRACE or PRM_ENTROPY_ORACLE is defined. The library, the CLI and the wasm module never define
// them (only the study's own copies of the decoder objects do), so their code and behaviour are unchanged.
//   PRM_ENTROPY_TRACE:  the values the decoder's range-coded sections yield, with their contexts, and every decision.
//   PRM_ENTROPY_ORACLE: the range decoder hands out a traced decode's decisions and direct bits from memory, with no
//                       arithmetic and no model update: the decode then costs what everything but §5 costs.
//   PRM_ENTROPY_VALUE_ORACLE (with PRM_ENTROPY_ORACLE): CLERS symbols, position residuals and §9.5 integers are
//                       handed out whole as well (no binarization, no Rice state), the other decisions as above: the
//                       decode then costs what everything but the entropy layer costs.
//   PRM_ENTROPY_RANS (with both oracles): those values are decoded from the study's static rANS streams instead
//                       (bench/entropy_study/rans_in_situ.h): a faster entropy layer inside the real decoder.
#pragma once

#if defined(PRM_ENTROPY_TRACE)
#include <cstddef>
#include <cstdint>

namespace prm::codec::entropy_trace {

// The hooks (the study's capture, bench/entropy_study/trace_capture.cpp, defines them):
//   block:      a range decoder starts on `size` bytes (§5.6); models of earlier blocks are never used again
//   clers:      §6.5.1 a CLERS symbol with its context; s_possible: the S decision was coded (two or more pieces)
//   residual:   §10.4.1 a position residual; ctx = axis * kResidualContexts + context; up, down: its bounds
//   signed_int: §9.5 a signed integer with its SignedIntModel, its sign model and max_class
//   value_begin: one of the three above starts (its decisions are not "other" decisions)
//   bit:        one modelled decision of any kind (§5.3);  direct: `count` direct bits of value v (§5.4)
void block(size_t size);
void clers(uint32_t ctx, uint32_t symbol, int s_possible);
void residual(uint32_t ctx, int64_t r, int64_t up, int64_t down);
void signed_int(const void* model, const void* sign, int max_class, int64_t v);
void value_begin();
void bit(uint32_t b);
void direct(int count, uint32_t v);

}  // namespace prm::codec::entropy_trace

#define PRM_ENTROPY_TRACE_CALL(call) ::prm::codec::entropy_trace::call
#else
#define PRM_ENTROPY_TRACE_CALL(call) ((void)0)
#endif

#if defined(PRM_ENTROPY_ORACLE)
#include <cstdint>

namespace prm::codec::entropy_trace {
extern const uint8_t* oracle_bits;     // the next decision
extern const uint32_t* oracle_direct;  // the next decode_direct's value
extern const uint8_t* oracle_clers;    // with PRM_ENTROPY_VALUE_ORACLE: the next CLERS symbol,
extern const int64_t* oracle_residual; // position residual
extern const int64_t* oracle_signed;   // and §9.5 integer
}  // namespace prm::codec::entropy_trace

#define PRM_ENTROPY_ORACLE_BIT() return static_cast<int>(*::prm::codec::entropy_trace::oracle_bits++)
#define PRM_ENTROPY_ORACLE_DIRECT() return *::prm::codec::entropy_trace::oracle_direct++
#else
#define PRM_ENTROPY_ORACLE_BIT() ((void)0)
#define PRM_ENTROPY_ORACLE_DIRECT() ((void)0)
#endif

// PRM_ENTROPY_VALUE(kind, x): true after setting x to the value oracle's next value of `kind` (clers, residual,
// signed); false (and no code) in every other build. PRM_ENTROPY_RETURN_VALUE(kind, x): the same as a statement that
// returns true, nothing at all in every other build (a dead `if (false) return` still moved GCC's block layout).
#if defined(PRM_ENTROPY_RANS)
#include "rans_in_situ.h"
#define PRM_ENTROPY_VALUE(kind, x) ((x = ::entropy_study::in_situ::next_##kind()), true)
#elif defined(PRM_ENTROPY_VALUE_ORACLE)
#define PRM_ENTROPY_VALUE(kind, x) ((x = *::prm::codec::entropy_trace::oracle_##kind++), true)
#else
#define PRM_ENTROPY_VALUE(kind, x) false
#endif
#if defined(PRM_ENTROPY_VALUE_ORACLE)
#define PRM_ENTROPY_RETURN_VALUE(kind, x) \
  do {                                    \
    (void)PRM_ENTROPY_VALUE(kind, x);     \
    return true;                          \
  } while (0)
#else
#define PRM_ENTROPY_RETURN_VALUE(kind, x) ((void)0)
#endif
