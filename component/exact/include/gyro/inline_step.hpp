// GYRO_INLINE_STEP: a function on the tick's path that is to be inlined wherever the compiler can
// be told to, except where code is built for size (-Os). For advance(), the tick's innermost step
// (GCC at -O2 calls it otherwise, and the call is a fifth of its cost; at -Os, inlined, it costs
// the Cortex-M targets' tick 400 to 700 bytes more stack), and for the flight component's parts'
// once-per-tick calls: GCC does not inline a template's member called once on its own, and step()
// then pays the calls and the copies across them (docs/performance.md).
#pragma once

#if defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__)
#define GYRO_INLINE_STEP [[gnu::always_inline]] inline
#else
#define GYRO_INLINE_STEP inline
#endif
