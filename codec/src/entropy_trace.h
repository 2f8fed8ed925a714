// A bench-only hook for the entropy-layer study (bench/entropy_study/, bench/README.md "hdecode8"): the values the
// decoder's range-coded sections yield, with their contexts. Compiled to nothing unless PRM_ENTROPY_TRACE is defined;
// the library, the CLI and the wasm module never define it (only the study's own copy of the decoder objects does),
// so their code and behaviour are unchanged.
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
//   bit:        one modelled decision of any kind (§5.3);  direct: `count` direct bits (§5.4)
void block(size_t size);
void clers(uint32_t ctx, uint32_t symbol, int s_possible);
void residual(uint32_t ctx, int64_t r, int64_t up, int64_t down);
void signed_int(const void* model, const void* sign, int max_class, int64_t v);
void bit();
void direct(int count);

}  // namespace prm::codec::entropy_trace

#define PRM_ENTROPY_TRACE_CALL(call) ::prm::codec::entropy_trace::call
#else
#define PRM_ENTROPY_TRACE_CALL(call) ((void)0)
#endif
