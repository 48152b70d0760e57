#include "pil_flight.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/pil/harness.hpp"
#include "pil_connection.hpp"
#include "sil_runner.hpp"
#include "wire_faults.hpp"

namespace gyro::sil {

namespace {

using Clock = std::chrono::steady_clock;

// What the PIL columns of one CSV row are made of.
struct PilRow {
  bool ran{false};
  std::uint64_t step_clocks{0};
  double instructions_per_clock{0};
  pil::TickOut report{};
  std::uint32_t wire_faults{0};
};

// The PIL columns, each name with its value: f(name, value). The one list the header and the
// rows are made from.
template <typename F>
void for_each_pil_column(const PilRow& p, F&& f) {
  const pil::TickOut& r = p.report;
  const auto instructions = static_cast<double>(p.step_clocks) * p.instructions_per_clock;
  f("pil_ran", std::uint64_t{p.ran ? 1u : 0u});
  f("pil_step_clocks", p.ran ? p.step_clocks : 0u);
  f("pil_step_instructions", p.ran ? static_cast<std::uint64_t>(std::llround(instructions)) : 0u);
  f("pil_overruns", std::uint64_t{r.overruns});
  f("pil_skipped", std::uint64_t{r.skipped});
  f("pil_readings", std::uint64_t{r.port.readings});
  f("pil_timeouts", std::uint64_t{r.port.timeouts});
  f("pil_bus_errors", std::uint64_t{r.port.bus_errors});
  f("pil_duplicates", std::uint64_t{r.port.duplicates});
  f("pil_frames_lost", std::uint64_t{r.port.frames_lost});
  f("pil_crc_errors", std::uint64_t{r.crc_errors});
  f("pil_wire_faults", std::uint64_t{p.wire_faults});
}

const std::vector<std::string_view>& pil_columns() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> n;
    for_each_pil_column(PilRow{}, [&](std::string_view name, std::uint64_t) { n.push_back(name); });
    return n;
  }();
  return names;
}

std::uint32_t low32(std::uint64_t v) noexcept { return static_cast<std::uint32_t>(v & 0xFFFFFFFFu); }

// Refuses to let QEMU replace anything at the socket path but a stale socket.
void check_socket_path(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && !S_ISSOCK(st.st_mode)) {
    throw RunError("PIL socket path " + path + " exists and is not a socket: not replacing it");
  }
}

// Removes the socket QEMU left behind (a socket only: nothing else is touched).
void remove_socket(const std::string& path) noexcept {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISSOCK(st.st_mode)) ::unlink(path.c_str());
}

template <typename T>
class PilFlightComputer final : public FlightComputer<T> {
 public:
  PilFlightComputer(GyroPort<T>& hardware, const PilOptions& options, PilSummary& summary)
      : hardware_(hardware), options_(options), summary_(summary) {
    if (!options.firmware.empty()) {
      check_socket_path(options.socket);
      qemu_.emplace(qemu_command(options.qemu, options.machine, options.firmware, options.socket),
                    options.target_console);
    }
    socket_.emplace(options.socket, 10.0, [this] { return !qemu_ || qemu_->running(); });
  }

  ~PilFlightComputer() override {
    if (qemu_ && !stopped_) {
      try {
        send(pil::encode_stop<T>(1, harness_seq_++));
      } catch (const RunError&) {  // the line is gone: QemuProcess terminates QEMU
      }
    }
    if (qemu_) {
      socket_.reset();
      qemu_.reset();  // terminates QEMU if it still runs
      remove_socket(options_.socket);
    }
  }

  [[nodiscard]] ConfigCheck configure(const GyroComponentConfig<T>& config) override {
    // A target in the other precision says hello in frames this decoder refuses.
    const char* const run = sizeof(T) == 4 ? "float" : "double";
    const char* const other = sizeof(T) == 4 ? "double" : "float";
    const std::string mismatch = std::string("PIL link: the target's hello is not in ") + run + ": a " + other +
                                 " image? (run it with --precision " + other + ")";
    pil::Hello hello;
    if (!pil::decode_hello<T>(receive(mismatch.c_str()), hello)) throw RunError(mismatch);
    if (hello.version != pil::kProtocolVersion || hello.real_bytes != sizeof(T)) {
      throw RunError("PIL link: target protocol " + std::to_string(hello.version) + " with " +
                     std::to_string(hello.real_bytes) + "-byte reals; expected protocol " +
                     std::to_string(pil::kProtocolVersion) + " with " + std::to_string(sizeof(T)));
    }
    summary_.target_real_bytes = hello.real_bytes;
    summary_.timer_hz = hello.timer_hz;
    pil::Config<T> c;
    c.component = config;
    const double period = std::round(static_cast<double>(config.tick_s) * static_cast<double>(hello.timer_hz));
    c.timer_period = options_.tick_clocks.value_or(period >= 1.0 && period <= 4e9 ? static_cast<std::uint32_t>(period) : 0u);
    summary_.tick_clocks = c.timer_period;
    send(pil::encode_config(c, harness_seq_++));
    pil::ConfigAck ack;
    if (!pil::decode_config_ack<T>(receive(), ack)) throw RunError("PIL link: no configuration verdict from the target");
    refused_field_ = ack.field.data();
    return ConfigCheck{ack.status, ack.status == Status::kOk ? nullptr : refused_field_.c_str()};
  }

  // The target activates itself once configured; its first report names its first tick.
  [[nodiscard]] Status activate() override {
    const pil::TickOut first = receive_report();
    if (first.has_previous) throw RunError("PIL link: the target reported a cycle before its first");
    next_tick_ = first.next_tick;
    start_ = Clock::now();
    return Status::kOk;
  }

  [[nodiscard]] std::optional<Status> step(std::uint64_t tick, const GuidanceInput<T>& in) override {
    if (in.request != ModeRequest::kNone) pending_request_ = in.request;  // held over skipped ticks
    faults_ = active_wire_faults(options_.faults, tick);
    ran_ = false;
    if (tick < next_tick_) return std::nullopt;  // the target skipped it after an overrun
    if (tick != next_tick_) {
      throw RunError("PIL link: the target runs tick " + std::to_string(next_tick_) + ", the host is at " +
                     std::to_string(tick));
    }
    send_tick(tick, in);
    const pil::TickOut report = receive_report();
    if (!report.has_previous || report.previous_tick != low32(tick)) {
      throw RunError("PIL link: the report is not of tick " + std::to_string(tick));
    }
    take_torque(report.gyro_bytes);
    if (!pil::decode_telemetry(receive(), telemetry_)) throw RunError("PIL link: no telemetry for tick " + std::to_string(tick));
    telemetry_.tick = tick;
    next_tick_ = tick + static_cast<std::uint32_t>(report.next_tick - low32(tick));

    ran_ = true;
    step_clocks_ = report.step_counts;
    summary_.cycles += 1;
    summary_.step_clocks_total += report.step_counts;
    if (report.step_counts > summary_.step_clocks_worst) {
      summary_.step_clocks_worst = report.step_counts;
      summary_.worst_tick = tick;
    }
    summary_.skipped = report.skipped;
    summary_.overruns = report.overruns;
    summary_.last_report = report;
    return report.step_status;
  }

  [[nodiscard]] const GyroTelemetry<T>& telemetry() const override { return telemetry_; }
  [[nodiscard]] GyroMode mode() const override { return telemetry_.mode; }

  [[nodiscard]] std::span<const std::string_view> extra_columns() const override { return pil_columns(); }
  void write_extras(CsvWriter& csv) const override {
    const PilRow row{ran_, step_clocks_, summary_.instructions_per_clock(), summary_.last_report, faults_};
    for_each_pil_column(row, [&csv](std::string_view, std::uint64_t v) { csv.integer(v); });
  }

  void finish() override {
    summary_.exchange_wall_s = std::chrono::duration<double>(Clock::now() - start_).count();
    send(pil::encode_stop<T>(0, harness_seq_++));
    stopped_ = true;
    // The target exits on the stop and QEMU closes the line: closing ours first could make QEMU
    // drop the stop's last bytes and leave the target waiting.
    if (!socket_->wait_closed(10.0)) throw RunError("PIL link: the target did not end after the stop");
    if (qemu_) {
      summary_.qemu_exit = qemu_->wait(10.0);
      if (summary_.qemu_exit != 0) {
        throw RunError("QEMU ended with status " + std::to_string(summary_.qemu_exit) + " after the run");
      }
    }
  }

 private:
  void send(const pil::HarnessFrame<T>& f) {
    std::array<std::uint8_t, pil::kHarnessFrameBytes<T>> bytes{};
    const std::size_t n = link::encode_frame(f, bytes);
    socket_->write(std::span<const std::uint8_t>(bytes.data(), n));
  }

  [[nodiscard]] pil::HarnessFrame<T> receive(const char* garbled = "PIL link: garbled harness frame from the target") {
    const std::uint32_t faults = decoder_.counters().faults();
    pil::HarnessFrame<T> f;
    for (;;) {
      (void)decoder_.push(socket_->read_byte(options_.timeout_s));
      if (decoder_.next(f)) return f;
      if (decoder_.counters().faults() != faults) throw RunError(garbled);
    }
  }

  [[nodiscard]] pil::TickOut receive_report() {
    pil::TickOut t;
    if (!pil::decode_tick_out<T>(receive(), t)) throw RunError("PIL link: expected the target's tick report");
    return t;
  }

  // The electronics' side of tick k: the stub's conversion as a pickoff frame, through the
  // wire faults, inside the tick's record with the guidance input.
  void send_tick(std::uint64_t tick, const GuidanceInput<T>& in) {
    std::vector<std::uint8_t> wire;
    PickoffReading<T> reading;
    if (hardware_.read_pickoffs(reading) == PortStatus::kOk) {
      std::array<std::uint8_t, link::kGyroLinkFrameBytes<T>> frame{};
      const std::size_t n = link::encode_frame(link::encode_pickoff(reading, downlink_seq_++), frame);
      wire = faulted_downlink(std::span<const std::uint8_t>(frame.data(), n), faults_, tick);
    }
    if (wire.size() > 255u) throw RunError("PIL link: more than 255 gyro-link bytes in one tick");
    pil::TickIn<T> t;
    t.tick = low32(tick);
    t.gyro_bytes = static_cast<std::uint8_t>(wire.size());
    t.guidance = in;
    t.guidance.request = pending_request_;
    pending_request_ = ModeRequest::kNone;
    std::array<std::uint8_t, pil::kHarnessFrameBytes<T>> bytes{};
    const std::size_t n = link::encode_frame(pil::encode_tick_in(t, harness_seq_++), bytes);
    wire.insert(wire.begin(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    socket_->write(wire);
  }

  // The target's torque frames of the cycle: the newest good one is latched by the stub
  // (nothing arrives while the link is stalled: the stub holds the previous command).
  void take_torque(std::uint8_t count) {
    bool fresh = false;
    Vector2<T> torque = Vector2<T>::Zero();
    for (std::uint8_t i = 0; i < count; ++i) {
      const std::uint8_t b = socket_->read_byte(options_.timeout_s);
      if (has_wire_fault(faults_, WireFaultKind::kStall)) continue;
      (void)uplink_.push(b);
      for (link::GyroLinkFrame<T> f; uplink_.next(f);) fresh = link::decode_torque(f, torque) || fresh;
    }
    summary_.uplink = uplink_.counters();
    if (fresh && hardware_.write_torquer(torque) == PortStatus::kOk) ++summary_.torque_commands;
  }

  GyroPort<T>& hardware_;  // the gyro hardware (the simulated gyro): its port plays the electronics
  PilOptions options_;
  PilSummary& summary_;
  std::optional<QemuProcess> qemu_;
  std::optional<SerialSocket> socket_;
  pil::HarnessDecoder<T> decoder_{};
  link::FrameDecoder<link::GyroLinkMessages<T>> uplink_{};
  GyroTelemetry<T> telemetry_{};
  std::string refused_field_;
  std::uint64_t next_tick_{0};
  ModeRequest pending_request_{ModeRequest::kNone};
  std::uint32_t faults_{0};
  bool ran_{false};
  std::uint64_t step_clocks_{0};
  std::uint8_t harness_seq_{0};
  std::uint8_t downlink_seq_{0};
  bool stopped_{false};
  Clock::time_point start_{Clock::now()};
};

}  // namespace

std::unique_ptr<FlightComputer<float>> make_pil_flight(GyroPort<float>& hardware, const PilOptions& options,
                                                       PilSummary& summary) {
  return std::make_unique<PilFlightComputer<float>>(hardware, options, summary);
}
std::unique_ptr<FlightComputer<double>> make_pil_flight(GyroPort<double>& hardware, const PilOptions& options,
                                                        PilSummary& summary) {
  return std::make_unique<PilFlightComputer<double>>(hardware, options, summary);
}

}  // namespace gyro::sil
