// Compiled with -std=c++17 -fno-exceptions -fno-rtti -Werror: every public header of the
// libraries, instantiated for float and double. Building this file is the check. It is also
// the translation unit that scripts/static-analysis.sh runs clang-tidy and cppcheck on, which
// requires every header under component/, port/, hil_stub/, examples/ and pil/ to be included here by name.
#include "gyro/arctangent.hpp"
#include "gyro/attitude.hpp"
#include "gyro/component_config.hpp"
#include "gyro/component_types.hpp"
#include "gyro/config_check.hpp"
#include "gyro/config_fields.hpp"
#include "gyro/enum_names.hpp"
#include "gyro/error_sources.hpp"
#include "gyro/estimator.hpp"
#include "gyro/fault_monitors.hpp"
#include "gyro/flag_counters.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "gyro/guidance_gate.hpp"
#include "gyro/inline_step.hpp"
#include "gyro/exact_step_check.hpp"
#include "gyro/mode_logic.hpp"
#include "gyro/nutation.hpp"
#include "gyro/nutation_tracker.hpp"
#include "gyro/persistence.hpp"
#include "gyro/pickoff_gate.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/rotor_transition.hpp"
#include "gyro/saturate.hpp"
#include "gyro/scalar_traits.hpp"
#include "gyro/spin_readback.hpp"
#include "gyro/seeker_component_example.hpp"
#include "gyro/board/register_board_port.hpp"
#include "gyro/status.hpp"
#include "gyro/stop_protection.hpp"
#include "gyro/tick_tracker.hpp"
#include "gyro/torque_law.hpp"
#include "gyro/torquer_axes.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {
template struct RotorTransition<float>;
template struct RotorTransition<double>;
template Status make_transition<float>(const RotorParameters<float>&, float, RotorTransition<float>&);
template Status make_transition<double>(const RotorParameters<double>&, double,
                                        RotorTransition<double>&);
template Status nutation_amplitude<float>(const RotorParameters<float>&, const Vector2<float>&,
                                          const Vector2<float>&, Vector2<float>&);
template ConfigCheck check_exact_step<float>(float, float, float, float, float, float, const ExactStepFields&);
template ConfigCheck check_exact_step<double>(double, double, double, double, double, double,
                                              const ExactStepFields&);
template Status nutation_amplitude<double>(const RotorParameters<double>&, const Vector2<double>&,
                                           const Vector2<double>&, Vector2<double>&);
}  // namespace gyro

#include "gyro/gyro_component.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"

namespace gyro {
template class GyroModel<float>;
template class GyroModel<double>;
template class GyroComponent<float>;
template class GyroComponent<double>;
}  // namespace gyro

#include "gyro/fault_schedule.hpp"
#include "gyro/noise.hpp"
#include "gyro/pickoff_electronics.hpp"
#include "gyro/report_plant.hpp"
#include "gyro/torquer_electronics.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {
template class NoiseStream<float>;
template class NoiseStream<double>;
// SimulatedGyro is final: its public non-virtual destructor cannot be reached through a base
// (GyroPort's is protected). clang-tidy 14's check does not exempt final classes.
template class SimulatedGyro<float>;   // NOLINT(cppcoreguidelines-virtual-class-destructor)
template class SimulatedGyro<double>;  // NOLINT(cppcoreguidelines-virtual-class-destructor)
}  // namespace gyro

#include "gyro/sil_loop.hpp"

namespace gyro {
template class SilLoop<float, GyroComponent<float>>;
template class SilLoop<double, GyroComponent<double>>;
template GuidanceInput<float> guidance_input<float>(const GuidanceCommand<float>&, const BodySample<float>&) noexcept;
template GuidanceInput<double> guidance_input<double>(const GuidanceCommand<double>&,
                                                      const BodySample<double>&) noexcept;
template Matrix3<float> pitch_then_yaw_turn<float>(const Vector2<float>&, float) noexcept;
template Matrix3<double> pitch_then_yaw_turn<double>(const Vector2<double>&, double) noexcept;
template BodySample<float> turning_body<float>(const Matrix3<float>&, const Vector2<float>&) noexcept;
template BodySample<double> turning_body<double>(const Matrix3<double>&, const Vector2<double>&) noexcept;
}  // namespace gyro

#include "gyro/link/byte_fifo.hpp"
#include "gyro/link/byte_link.hpp"
#include "gyro/link/cmsdk_apb_uart.hpp"
#include "gyro/link/crc16.hpp"
#include "gyro/link/frame.hpp"
#include "gyro/link/frame_decoder.hpp"
#include "gyro/link/gyro_link_messages.hpp"
#include "gyro/link/link_gyro_port.hpp"
#include "gyro/link/saturating_count.hpp"
#include "gyro/link/wire.hpp"
#include "gyro/rate_group.hpp"

namespace gyro {
template class link::ByteFifo<64>;
template class link::FifoLink<64, 32>;  // NOLINT(cppcoreguidelines-virtual-class-destructor): final
template class link::FrameDecoder<link::GyroLinkMessages<float>>;
template class link::FrameDecoder<link::GyroLinkMessages<double>>;
template class link::WireWriter<16>;
template class link::WireReader<16>;
template class LinkGyroPort<float>;   // NOLINT(cppcoreguidelines-virtual-class-destructor): final
template class LinkGyroPort<double>;  // NOLINT(cppcoreguidelines-virtual-class-destructor): final
template link::GyroLinkFrame<float> link::encode_pickoff<float>(const PickoffReading<float>&, std::uint8_t) noexcept;
template link::GyroLinkFrame<double> link::encode_pickoff<double>(const PickoffReading<double>&, std::uint8_t) noexcept;
template bool link::decode_pickoff<float>(const link::GyroLinkFrame<float>&, PickoffReading<float>&) noexcept;
template bool link::decode_pickoff<double>(const link::GyroLinkFrame<double>&, PickoffReading<double>&) noexcept;
template link::GyroLinkFrame<float> link::encode_torque<float>(const Eigen::Matrix<float, 2, 1>&, std::uint8_t) noexcept;
template link::GyroLinkFrame<double> link::encode_torque<double>(const Eigen::Matrix<double, 2, 1>&,
                                                                 std::uint8_t) noexcept;
template bool link::decode_torque<float>(const link::GyroLinkFrame<float>&, Eigen::Matrix<float, 2, 1>&) noexcept;
template bool link::decode_torque<double>(const link::GyroLinkFrame<double>&, Eigen::Matrix<double, 2, 1>&) noexcept;
}  // namespace gyro

#include "gyro/pil/harness.hpp"

namespace gyro::pil {
template HarnessFrame<float> encode_config<float>(const Config<float>&, std::uint8_t) noexcept;
template HarnessFrame<double> encode_config<double>(const Config<double>&, std::uint8_t) noexcept;
template bool decode_config<float>(const HarnessFrame<float>&, Config<float>&) noexcept;
template bool decode_config<double>(const HarnessFrame<double>&, Config<double>&) noexcept;
template HarnessFrame<float> encode_tick_in<float>(const TickIn<float>&, std::uint8_t) noexcept;
template HarnessFrame<double> encode_tick_in<double>(const TickIn<double>&, std::uint8_t) noexcept;
template bool decode_tick_in<float>(const HarnessFrame<float>&, TickIn<float>&) noexcept;
template bool decode_tick_in<double>(const HarnessFrame<double>&, TickIn<double>&) noexcept;
template HarnessFrame<float> encode_tick_out<float>(const TickOut&, std::uint8_t) noexcept;
template bool decode_tick_out<double>(const HarnessFrame<double>&, TickOut&) noexcept;
template HarnessFrame<float> encode_telemetry<float>(const GyroTelemetry<float>&, std::uint8_t) noexcept;
template HarnessFrame<double> encode_telemetry<double>(const GyroTelemetry<double>&, std::uint8_t) noexcept;
template bool decode_telemetry<float>(const HarnessFrame<float>&, GyroTelemetry<float>&) noexcept;
template bool decode_telemetry<double>(const HarnessFrame<double>&, GyroTelemetry<double>&) noexcept;
template HarnessFrame<float> encode_hello<float>(const Hello&, std::uint8_t) noexcept;
template bool decode_hello<double>(const HarnessFrame<double>&, Hello&) noexcept;
template HarnessFrame<double> encode_config_ack<double>(const ConfigAck&, std::uint8_t) noexcept;
template bool decode_config_ack<float>(const HarnessFrame<float>&, ConfigAck&) noexcept;
template HarnessFrame<float> encode_stop<float>(std::uint8_t, std::uint8_t) noexcept;
}  // namespace gyro::pil

namespace gyro {
template class link::FrameDecoder<pil::HarnessMessages<float>>;
template class link::FrameDecoder<pil::HarnessMessages<double>>;
}  // namespace gyro

#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"

namespace gyro {
namespace flight_rules_check {
struct IgnoreStep {
  template <typename T>
  void operator()(int /*step*/, T /*time_s*/, const GyroModel<T>& /*model*/,
                  const Matrix3<T>& /*R_earth_to_body*/) const noexcept {}
};
}  // namespace flight_rules_check
template struct ReportSample<float>;
template struct ReportSample<double>;
template struct SeekerExample<float>;
template struct SeekerExample<double>;
template SampleRunSummary run_report_sample<float, flight_rules_check::IgnoreStep>(
    float, int, flight_rules_check::IgnoreStep&&) noexcept;
template SampleRunSummary run_report_sample<double, flight_rules_check::IgnoreStep>(
    double, int, flight_rules_check::IgnoreStep&&) noexcept;
}  // namespace gyro

#include "gyro/dormand_prince8.hpp"
#include "gyro/gimbal_dynamics.hpp"
#include "gyro/gimbal_kinematics.hpp"
#include "gyro/gimbal_plant.hpp"
#include "gyro/gimbal_plant_config.hpp"
#include "gyro/gimbal_stop.hpp"
#include "gyro/gimbal_substep_control.hpp"
#include "gyro/seeker_gimbal.hpp"
#include "gyro/sil_contract.hpp"

namespace gyro {
template int substeps_after_failure<float>(int, float, float, int) noexcept;
template int substeps_after_failure<double>(int, double, double, int) noexcept;
template int substeps_after_success<float>(int, float, float) noexcept;
template int substeps_after_success<double>(int, double, double) noexcept;
template class GimbalPlant<float>;
template class GimbalPlant<double>;
template ConfigCheck check<float>(const GimbalPlantConfig<float>&) noexcept;
template ConfigCheck check<double>(const GimbalPlantConfig<double>&) noexcept;
template GimbalParameters<float> make_gimbal_parameters<float>(const GimbalPlantConfig<float>&) noexcept;
template GimbalParameters<double> make_gimbal_parameters<double>(const GimbalPlantConfig<double>&) noexcept;
template GimbalAccelerations<float> gimbal_accelerations<float>(const GimbalParameters<float>&,
                                                                const GimbalJointState<float>&,
                                                                const GimbalDrive<float>&,
                                                                const BodyInstant<float>&) noexcept;
template GimbalAccelerations<double> gimbal_accelerations<double>(const GimbalParameters<double>&,
                                                                  const GimbalJointState<double>&,
                                                                  const GimbalDrive<double>&,
                                                                  const BodyInstant<double>&) noexcept;
template bool resolve_gimbal_stop<float>(const GimbalStop<float>&, const GimbalInertias<float>&,
                                         GimbalJointState<float>&) noexcept;
template bool resolve_gimbal_stop<double>(const GimbalStop<double>&, const GimbalInertias<double>&,
                                          GimbalJointState<double>&) noexcept;
template float gimbal_fastest_rate<float>(const GimbalPlantConfig<float>&) noexcept;
template double gimbal_fastest_rate<double>(const GimbalPlantConfig<double>&) noexcept;
template int gimbal_substeps<float>(const GimbalPlantConfig<float>&, float) noexcept;
template int gimbal_substeps<double>(const GimbalPlantConfig<double>&, double) noexcept;
template GimbalPlantConfig<float> seeker_gimbal_config<float>() noexcept;
template GimbalPlantConfig<double> seeker_gimbal_config<double>() noexcept;
template float gimbal_kinetic_energy<float>(const GimbalInertias<float>&, const GimbalBodyRates<float>&) noexcept;
template double gimbal_kinetic_energy<double>(const GimbalInertias<double>&, const GimbalBodyRates<double>&) noexcept;
}  // namespace gyro
