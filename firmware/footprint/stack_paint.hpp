// Stack measurement by painting, for the footprint images: the free stack below the caller
// is filled with a pattern, the code runs, and the lowest word no longer holding the
// pattern marks the deepest use. No interrupts run in these images, and Arm has no red
// zone below sp, so everything below the caller's frame is free to paint.
#pragma once

#include <cstdint>

extern "C" std::uint32_t __stack_limit[];  // mps2.ld: the lowest address of the stack

namespace gyro_fw {

constexpr std::uint32_t kStackPaint = 0xA5A5A5A5U;

inline std::uintptr_t stack_pointer() noexcept {
  std::uintptr_t sp;
  __asm__ volatile("mov %0, sp" : "=r"(sp));
  return sp;
}

// Fills the free stack from __stack_limit up to this function's stack pointer.
__attribute__((noinline)) inline void paint_stack() noexcept {
  volatile std::uint32_t* p = __stack_limit;
  const std::uintptr_t end = stack_pointer();
  while (reinterpret_cast<std::uintptr_t>(p) < end) *p++ = kStackPaint;
}

// The lowest address written since paint_stack().
__attribute__((noinline)) inline std::uintptr_t stack_low_water() noexcept {
  const volatile std::uint32_t* p = __stack_limit;
  while (*p == kStackPaint) ++p;
  return reinterpret_cast<std::uintptr_t>(p);
}

// Bytes of stack below the caller's frame that `run` uses.
template <typename F>
std::uintptr_t stack_used_by(F&& run) noexcept {
  paint_stack();
  const std::uintptr_t sp = stack_pointer();
  run();
  return sp - stack_low_water();
}

}  // namespace gyro_fw
