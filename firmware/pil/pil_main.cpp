// Processor-in-the-loop image (docs/pil.md): the flight component on the target, the gyro and
// the body on the host (gyro_sil --pil), over UART0 of the MPS2 board.
//
//   SysTick interrupt  -> RateGroup::release()             a tick every configured period
//   main loop          -> sleep until a tick is released
//                      -> timer paused: report the last cycle to the host, receive this
//                         tick's guidance input and the gyro-link bytes that arrived
//                      -> timer running: GyroComponent::step(tick) through LinkGyroPort
//                         (pickoff frames in, torque frame out), timed in core clocks
//                      -> RateGroup::end(): overrun if the next tick came meanwhile
//
// The component runs in the target's scalar (float on the M4F, double on the M7). Output on
// the semihosting console: one summary line when the host stops the run. Exit status: 0 run
// stopped by the host; 2 configuration refused; 3 the harness link broke.
#include <cstdint>

#include "cortex_m.hpp"
#include "fw_io.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/cmsdk_apb_uart.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "gyro/pil/harness.hpp"
#include "gyro/rate_group.hpp"
#include "host_link.hpp"
#include "semihosting.h"
#include "target_scalar.hpp"
#include "tick_timer.hpp"

using Scalar = gyro_fw::TargetScalar;

namespace {

constexpr std::uint32_t kCoreClockHz = 25000000u;  // MPS2 SYSCLK, also SysTick's clock
constexpr std::uint32_t kBaud = 115200u;

// The gyro link: bytes from the host's record of each tick go into rx(); the port's torque
// frames come out of tx() into the next report. The port drains what a tick's record brought
// (up to 255 bytes, the line's rate; gyro/pil/harness.hpp).
gyro::pil::GyroWire g_gyro_wire;
gyro::pil::GyroLinkPort<Scalar> g_port(g_gyro_wire);
gyro::GyroComponent<Scalar> g_component(g_port);
gyro::RateGroup g_rate_group;
gyro_fw::TickTimer g_timer;

// What the last cycle did, reported at the start of the next.
struct Cycle {
  bool ran{false};
  std::uint64_t tick{0};
  gyro::Status status{gyro::Status::kOk};
  std::uint64_t clocks{0};
};

struct StepStats {
  std::uint64_t total{0};
  std::uint64_t worst{0};
  std::uint64_t worst_tick{0};
  std::uint32_t rx_dropped{0};  // gyro-link bytes beyond the receive FIFO
};

void wait_for_release() noexcept {
  gyro_fw::disable_interrupts();
  while (!g_rate_group.pending()) {
    gyro_fw::wait_for_interrupt();
    gyro_fw::enable_interrupts();  // the SysTick handler runs here
    gyro_fw::disable_interrupts();
  }
  gyro_fw::enable_interrupts();
}

std::uint32_t low32(std::uint64_t v) noexcept { return static_cast<std::uint32_t>(v & 0xFFFFFFFFu); }

gyro::pil::TickOut report_of(const Cycle& last, std::uint64_t next_tick, std::uint8_t gyro_bytes) noexcept {
  const gyro::RateGroupTelemetry& rg = g_rate_group.telemetry();
  const gyro::link::DecoderCounters& dc = g_port.decoder_counters();
  gyro::pil::TickOut t;
  t.next_tick = low32(next_tick);
  t.has_previous = last.ran;
  t.previous_tick = low32(last.tick);
  t.step_status = last.status;
  t.step_counts = low32(last.clocks);
  t.gyro_bytes = gyro_bytes;
  t.released = low32(rg.released);
  t.cycles = low32(rg.cycles);
  t.skipped = low32(rg.skipped);
  t.overruns = rg.overruns;
  t.overrun = rg.overrun;
  t.port = g_port.counters();
  t.header_errors = dc.header_errors;
  t.crc_errors = dc.crc_errors;
  t.bytes_skipped = dc.bytes_skipped;
  t.decoder_frames = dc.frames;
  return t;
}

// The report of the last cycle: tick_out, the torque bytes the port queued, the telemetry.
void report(gyro_fw::HostLink<Scalar>& host, const Cycle& last, std::uint64_t next_tick) noexcept {
  const std::size_t queued = g_gyro_wire.tx().size();
  const auto gyro_bytes = static_cast<std::uint8_t>(queued > 255u ? 255u : queued);
  host.send(gyro::pil::encode_tick_out<Scalar>(report_of(last, next_tick, gyro_bytes), host.seq()));
  std::uint8_t b = 0;
  for (std::size_t i = 0; i < gyro_bytes && g_gyro_wire.tx().pop(b); ++i) host.send_byte(b);
  g_gyro_wire.tx().clear();  // (never more than 255 bytes: one torque frame per step)
  if (last.ran) host.send(gyro::pil::encode_telemetry(g_component.telemetry(), host.seq()));
}

[[noreturn]] void finish(int status, const char* why, const StepStats& s) noexcept {
  const gyro::RateGroupTelemetry& rg = g_rate_group.telemetry();
  const std::uint64_t cycles = rg.cycles == 0u ? 1u : rg.cycles;
  gyro_fw::Line() << "pil: " << why << ": " << static_cast<unsigned long>(rg.cycles) << " cycles, "
                  << static_cast<unsigned long>(rg.overruns) << " overruns, " << static_cast<unsigned long>(rg.skipped)
                  << " ticks skipped; step " << static_cast<unsigned long>(s.total / cycles) << " clocks mean, "
                  << static_cast<unsigned long>(s.worst) << " worst (tick " << static_cast<unsigned long>(s.worst_tick)
                  << "); gyro link: " << static_cast<unsigned long>(g_port.counters().readings) << " readings, "
                  << static_cast<unsigned long>(s.rx_dropped) << " bytes dropped\n";
  gyro_fw_exit(status);
}

}  // namespace

extern "C" void SysTick_Handler(void) {
  g_timer.on_interrupt();
  g_rate_group.release();
}

int main() {
  gyro::link::CmsdkApbUart uart(
      *reinterpret_cast<volatile gyro::link::CmsdkApbUartRegisters*>(gyro::link::kMps2Uart0Base));  // NOLINT
  (void)uart.enable(kCoreClockHz, kBaud);
  gyro_fw::HostLink<Scalar> host(uart);
  StepStats stats;

  gyro::pil::Hello hello;
  hello.real_bytes = sizeof(Scalar);
  hello.timer_hz = kCoreClockHz;
  host.send(gyro::pil::encode_hello<Scalar>(hello, host.seq()));

  gyro::pil::HarnessFrame<Scalar> frame;
  gyro::pil::Config<Scalar> config;
  if (!host.receive(frame) || !gyro::pil::decode_config(frame, config)) finish(3, "no configuration", stats);
  gyro::ConfigCheck check = g_component.configure(config.component);
  if (check.ok() && (config.timer_period < 2u || config.timer_period > gyro_fw::TickTimer::kMaxPeriod)) {
    check = {gyro::Status::kOutOfRange, "timer_period"};
  }
  host.send(gyro::pil::encode_config_ack<Scalar>(gyro::pil::make_config_ack(check), host.seq()));
  if (!check.ok()) finish(2, "configuration refused", stats);
  (void)g_component.activate();
  (void)g_timer.start(config.timer_period);

  Cycle last;
  gyro::pil::TickIn<Scalar> in;
  for (;;) {
    wait_for_release();
    g_timer.pause();
    std::uint64_t tick = 0;
    (void)g_rate_group.begin(tick);

    report(host, last, tick);
    if (!host.receive(frame)) finish(3, "harness link broken", stats);
    if (frame.type == gyro::link::frame_type<Scalar>(gyro::pil::kStop)) finish(0, "stopped by the host", stats);
    if (!gyro::pil::decode_tick_in(frame, in) || in.tick != low32(tick)) finish(3, "unexpected frame", stats);
    for (std::uint8_t i = 0; i < in.gyro_bytes; ++i) {
      if (!g_gyro_wire.rx().push(host.receive_byte())) ++stats.rx_dropped;
    }

    g_timer.resume();
    const std::uint64_t t0 = g_timer.now();
    const gyro::Status status = g_component.step(tick, in.guidance);
    const std::uint64_t t1 = g_timer.now();
    (void)g_rate_group.end();
#ifdef PIL_DEBUG
    if (tick < 4) gyro_fw::Line() << "tick " << static_cast<unsigned long>(tick) << " t0 " << static_cast<unsigned long>(t0) << " t1 " << static_cast<unsigned long>(t1) << " val " << static_cast<unsigned long>(gyro_fw::systick().val) << "\n";
#endif

    last = Cycle{true, tick, status, t1 - t0};
    stats.total += last.clocks;
    if (last.clocks > stats.worst) {
      stats.worst = last.clocks;
      stats.worst_tick = tick;
    }
  }
}
