// The flight side of a gyro_sil run, as the SIL loop sees it: the gyro component, configured,
// activated and stepped once per tick against the simulated gyro (its port). In process
// (LocalFlightComputer: GyroComponent with the stub as its port) or on an emulated target over
// a serial link (processor in the loop: pil_flight.hpp), behind the same calls, so the loop,
// the body, the guidance schedule, the stub and the CSV are one code path for both.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "csv_writer.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro::sil {

template <typename T>
class FlightComputer {
 public:
  FlightComputer() = default;
  FlightComputer(const FlightComputer&) = delete;
  FlightComputer& operator=(const FlightComputer&) = delete;
  virtual ~FlightComputer() = default;

  [[nodiscard]] virtual ConfigCheck configure(const GyroComponentConfig<T>& config) = 0;
  [[nodiscard]] virtual Status activate() = 0;
  // The component's tick k. nullopt: the flight computer did not run tick k (a processor in
  // the loop that overran skips ticks; telemetry() then still holds its last tick's).
  [[nodiscard]] virtual std::optional<Status> step(std::uint64_t tick, const GuidanceInput<T>& in) = 0;
  [[nodiscard]] virtual const GyroTelemetry<T>& telemetry() const = 0;
  [[nodiscard]] virtual GyroMode mode() const = 0;

  // Columns this flight computer adds after the standard ones, and their values this tick.
  [[nodiscard]] virtual std::span<const std::string_view> extra_columns() const { return {}; }
  virtual void write_extras(CsvWriter& /*csv*/) const {}
  // After the last tick (a processor in the loop stops its target here).
  virtual void finish() {}
};

template <typename T>
class LocalFlightComputer final : public FlightComputer<T> {
 public:
  // `hardware`: the gyro behind its port (the simulated gyro in a SIL run).
  explicit LocalFlightComputer(GyroPort<T>& hardware) : component_(hardware) {}

  [[nodiscard]] ConfigCheck configure(const GyroComponentConfig<T>& config) override {
    return component_.configure(config);
  }
  [[nodiscard]] Status activate() override { return component_.activate(); }
  [[nodiscard]] std::optional<Status> step(std::uint64_t tick, const GuidanceInput<T>& in) override {
    return component_.step(tick, in);
  }
  [[nodiscard]] const GyroTelemetry<T>& telemetry() const override { return component_.telemetry(); }
  [[nodiscard]] GyroMode mode() const override { return component_.mode(); }

 private:
  GyroComponent<T> component_;
};

}  // namespace gyro::sil
