// Processor in the loop (docs/pil.md): the flight component runs on an emulated Cortex-M
// (firmware/pil/, the gyro_fw_pil image under QEMU) and the SIL loop's stub, body and guidance
// stay on the host. The FlightComputer made here plays the gyro electronics on the serial
// line: each tick it sends the stub's pickoff conversion as a pickoff frame (through the wire
// faults asked for) with the tick's guidance input, and applies the torque frame the target
// answers with to the stub. Lockstep: the target runs a tick only with the host's inputs for
// it, in its own time, which stands still while the host works.
#pragma once

#include <memory>

#include "flight_computer.hpp"
#include "pil_options.hpp"

namespace gyro::sil {

// The flight computer on the target, with `hardware` (the simulated gyro, behind its port) on
// the host; `summary` is filled in as the run goes. Starts QEMU when options.firmware is set,
// else connects to the one listening on options.socket.
[[nodiscard]] std::unique_ptr<FlightComputer<float>> make_pil_flight(GyroPort<float>& hardware,
                                                                     const PilOptions& options,
                                                                     PilSummary& summary);
[[nodiscard]] std::unique_ptr<FlightComputer<double>> make_pil_flight(GyroPort<double>& hardware,
                                                                      const PilOptions& options,
                                                                      PilSummary& summary);

}  // namespace gyro::sil
