// The scalar a footprint image runs in: float on a single-precision FPU (Cortex-M4F, __ARM_FP
// without the double-precision bit 0x8), else double.
#pragma once

namespace gyro_fw {
#if defined(__ARM_FP) && !(__ARM_FP & 0x8)
using TargetScalar = float;
#else
using TargetScalar = double;
#endif
}  // namespace gyro_fw
