// Instructions of every GyroComponent::step call on the target, exact, under
// qemu-system-arm -icount shift=0 (one instruction = 1 ns of virtual time), on the case of
// bench/component_tick_case.hpp (the x86-64 figure's case: the seeker example slewing on a
// turning body; steady spin readback, then one changing every tick). scripts/tick-cost.sh runs
// it; the method is in docs/performance.md ("On the targets").
//
// The only guest clock is SysTick on the MPS2's 25 MHz core clock: one count per 40
// instructions. Vernier: the case is run kPhases = 40 times, each after a pad of 3 (r + 1)
// instructions (r = 0 .. 39) behind a fresh start of the timer. Every run executes the same
// instructions (the component and the stub are bit-for-bit deterministic), so an event (a
// timer read before or after a step) happens at the same instruction u in every run, and run
// r reads floor((u + 3 (r + 1)) / 40) plus a constant. As 3 (r + 1) takes every residue
// modulo 40, the 40 readings fix u modulo 40, and the first run's reading gives the rest:
// each step's instructions are exact. A run whose readings fit no residue, or more than one,
// fails the image, and so does the check: pad(117) measured against pad(100) must come out
// exactly 51 instructions longer.
//
// Output (semihosting), per case:
//   case <steady|spin_down> scalar <float|double> ticks <n> overhead <instructions> check 51
//   tick <k> <instructions> <mode> <flags>         k = 1 .. n, the step's instructions
// (the two timer reads' own cost, `overhead`, taken off), its mode and flags after the step.
#include <cstdint>
#include <new>

#include "component_tick_case.hpp"
#include "cortex_m.hpp"
#include "fw_io.hpp"
#include "target_scalar.hpp"

using Scalar = gyro_fw::TargetScalar;

namespace {

constexpr unsigned kPhases = 40;          // instructions per SysTick count
constexpr std::uint32_t kTicks = 800;     // 600 caged, uncaging and settling, 200 in free flight
constexpr std::uint32_t kCountMask = 0xFFFFFFU;  // SysTick is a 24-bit down-counter

std::uint32_t g_start[kPhases][kTicks];  // timer counts at each step's start and end
std::uint32_t g_end[kPhases][kTicks];
std::uint32_t g_empty[kPhases][2];       // a measurement of nothing: the reads' own cost
std::uint32_t g_known[kPhases][4];       // measurements of pad(kShortPad) and pad(kLongPad)
constexpr std::uint32_t kShortPad = 100;
constexpr std::uint32_t kLongPad = 117;  // 3 * 17 = 51 instructions more: the method's check
std::uint8_t g_mode[kTicks];
std::uint32_t g_flags[kTicks];

// Counts since the timer's start (it counts down from kCountMask).
inline std::uint32_t timer_counts() noexcept { return kCountMask - gyro_fw::systick().val; }
inline void barrier() noexcept { __asm__ volatile("" ::: "memory"); }

void start_timer() noexcept {
  volatile gyro_fw::SysTickRegisters& r = gyro_fw::systick();
  r.ctrl = 0;
  r.load = kCountMask;
  r.val = 0;
  r.ctrl = (1U << 0) | (1U << 2);  // enabled, core clock, no interrupt
}

// 3 n instructions (n >= 1): the vernier's shift of every later instruction.
__attribute__((noipa)) void pad(std::uint32_t n) noexcept {
  __asm__ volatile("1: subs %0, %0, #1\n\tnop\n\tbne 1b" : "+r"(n) : : "cc");
}

// Timer reads around pad(n), the same instructions whatever n: for the method's check.
__attribute__((noipa)) void measure_pad(std::uint32_t n, std::uint32_t* readings) noexcept {
  readings[0] = timer_counts();
  pad(n);
  readings[1] = timer_counts();
}

struct TimerMeter {
  unsigned phase{0};
  const gyro::GyroComponent<Scalar>* component{nullptr};

  template <typename Call>
  gyro::Status measure(std::uint64_t tick, Call&& call) noexcept {
    const std::uint32_t begin = timer_counts();
    barrier();
    const gyro::Status st = call();
    barrier();
    const std::uint32_t end = timer_counts();
    if (tick >= 1 && tick <= kTicks) {
      const std::size_t i = static_cast<std::size_t>(tick - 1);
      g_start[phase][i] = begin;
      g_end[phase][i] = end;
      // Every run does the same work between its events: each writes these (the same values).
      g_mode[i] = static_cast<std::uint8_t>(component->telemetry().mode);
      g_flags[i] = component->telemetry().flags;
    }
    return st;
  }
};

// Static storage for the case's objects, built afresh for every run.
alignas(gyro::SimulatedGyro<Scalar>) unsigned char g_stub_storage[sizeof(gyro::SimulatedGyro<Scalar>)];
alignas(gyro::GyroComponent<Scalar>) unsigned char g_component_storage[sizeof(gyro::GyroComponent<Scalar>)];

// One run of the case after a pad of 3 (phase + 1) instructions; false if it failed.
__attribute__((noinline)) bool run_once(gyro_bench::TickCase which, unsigned phase) noexcept {
  start_timer();
  pad(phase + 1U);
  auto* stub = new (g_stub_storage) gyro::SimulatedGyro<Scalar>();
  auto* component = new (g_component_storage) gyro::GyroComponent<Scalar>(*stub);
  TimerMeter meter{phase, component};
  const std::uint32_t a = timer_counts();
  barrier();
  barrier();
  const std::uint32_t b = timer_counts();
  g_empty[phase][0] = a;
  g_empty[phase][1] = b;
  measure_pad(kShortPad, &g_known[phase][0]);
  measure_pad(kLongPad, &g_known[phase][2]);
  const gyro_bench::TickCaseResult r = gyro_bench::run_tick_case(which, kTicks, *stub, *component, meter);
  component->~GyroComponent();
  stub->~SimulatedGyro();
  return r.error == 0;
}

// The event's time in instructions (up to a constant shared by every event), from its readings
// in the kPhases runs; -1 if they fit no single residue.
long long event_time(const std::uint32_t* readings, std::size_t stride) noexcept {
  int found = -1;
  for (unsigned rho = 0; rho < kPhases; ++rho) {
    bool fits = true;
    const std::uint32_t base0 = (rho + 3U) / kPhases;
    for (unsigned r = 1; r < kPhases && fits; ++r) {
      const std::uint32_t expected = (rho + 3U * (r + 1U)) / kPhases - base0;
      fits = ((readings[r * stride] - readings[0]) & kCountMask) == expected;
    }
    if (fits) {
      if (found >= 0) return -1;
      found = static_cast<int>(rho);
    }
  }
  if (found < 0) return -1;
  return static_cast<long long>(readings[0]) * kPhases + static_cast<long long>((static_cast<unsigned>(found) + 3U) % kPhases);
}

bool measure_case(gyro_bench::TickCase which, const char* name) noexcept {
  for (unsigned phase = 0; phase < kPhases; ++phase) {
    if (!run_once(which, phase)) {
      gyro_fw::Line() << "case " << name << ": the run failed\n";
      return false;
    }
  }
  const long long empty = event_time(&g_empty[0][1], 2) - event_time(&g_empty[0][0], 2);
  const long long short_pad = event_time(&g_known[0][1], 4) - event_time(&g_known[0][0], 4);
  const long long long_pad = event_time(&g_known[0][3], 4) - event_time(&g_known[0][2], 4);
  if (long_pad - short_pad != 3 * static_cast<long long>(kLongPad - kShortPad)) {
    gyro_fw::Line() << "case " << name << ": the check failed: pad(" << static_cast<unsigned long>(kLongPad)
                    << ") - pad(" << static_cast<unsigned long>(kShortPad) << ") measured "
                    << static_cast<long>(long_pad - short_pad) << " instructions\n";
    return false;
  }
  gyro_fw::Line() << "case " << name << " scalar " << (sizeof(Scalar) == 4 ? "float" : "double") << " ticks "
                  << static_cast<unsigned long>(kTicks) << " overhead " << static_cast<long>(empty) << " check "
                  << static_cast<long>(long_pad - short_pad) << '\n';
  for (std::uint32_t i = 0; i < kTicks; ++i) {
    const long long begin = event_time(&g_start[0][i], kTicks);
    const long long end = event_time(&g_end[0][i], kTicks);
    if (begin < 0 || end < 0 || end < begin) {
      gyro_fw::Line() << "tick " << static_cast<unsigned long>(i + 1) << ": the readings fit no single phase\n";
      return false;
    }
    gyro_fw::Line() << "tick " << static_cast<unsigned long>(i + 1) << ' ' << static_cast<long>(end - begin - empty)
                    << ' ' << gyro::enum_name_or(static_cast<gyro::GyroMode>(g_mode[i]), "unknown") << ' '
                    << static_cast<unsigned long>(g_flags[i]) << '\n';
  }
  return true;
}

}  // namespace

int main() {
  const bool ok = measure_case(gyro_bench::TickCase::kSteady, "steady") &&
                  measure_case(gyro_bench::TickCase::kSpinDown, "spin_down");
  return ok ? 0 : 1;
}
