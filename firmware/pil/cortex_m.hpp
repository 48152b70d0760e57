// The few Cortex-M core registers and instructions the PIL image uses (ARMv7-M architecture
// reference manual, B3): interrupt masking, sleep, the NVIC's per-interrupt enable and pending
// bits, and the SysTick timer. No CMSIS.
#pragma once

#include <cstdint>

namespace gyro_fw {

struct SysTickRegisters {
  std::uint32_t ctrl;   // 0xE000E010: bit 0 enable, bit 1 interrupt, bit 2 core clock, bit 16 count flag
  std::uint32_t load;   // 0xE000E014: reload value (24 bits)
  std::uint32_t val;    // 0xE000E018: current value, counts down
  std::uint32_t calib;  // 0xE000E01C
};

inline volatile SysTickRegisters& systick() noexcept {
  return *reinterpret_cast<volatile SysTickRegisters*>(0xE000E010u);  // NOLINT: a fixed register address
}
inline volatile std::uint32_t& icsr() noexcept {  // Interrupt Control and State Register
  return *reinterpret_cast<volatile std::uint32_t*>(0xE000ED04u);  // NOLINT: a fixed register address
}
inline constexpr std::uint32_t kIcsrPendStSet = 1u << 26;  // the SysTick exception is pending

// NVIC, external interrupts 0..31.
inline void nvic_enable(unsigned irq) noexcept { *reinterpret_cast<volatile std::uint32_t*>(0xE000E100u) = 1u << irq; }   // NOLINT
inline void nvic_disable(unsigned irq) noexcept { *reinterpret_cast<volatile std::uint32_t*>(0xE000E180u) = 1u << irq; }  // NOLINT
inline void nvic_clear_pending(unsigned irq) noexcept { *reinterpret_cast<volatile std::uint32_t*>(0xE000E280u) = 1u << irq; }  // NOLINT

inline void disable_interrupts() noexcept { __asm__ volatile("cpsid i" ::: "memory"); }
inline void enable_interrupts() noexcept { __asm__ volatile("cpsie i\n\tisb" ::: "memory"); }
// Sleeps until an interrupt is pending (also one masked by PRIMASK: it wakes, is not taken).
inline void wait_for_interrupt() noexcept { __asm__ volatile("wfi" ::: "memory"); }

inline std::uint32_t save_and_disable_interrupts() noexcept {
  std::uint32_t primask = 0;
  __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
  return primask;
}
inline void restore_interrupts(std::uint32_t primask) noexcept {
  __asm__ volatile("msr primask, %0\n\tisb" ::"r"(primask) : "memory");
}

}  // namespace gyro_fw
