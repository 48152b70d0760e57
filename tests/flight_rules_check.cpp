// Compiled with -std=c++17 -fno-exceptions -fno-rtti -Werror: every public header of the
// libraries, instantiated for float and double. Building this file is the check.
#include "gyro/nutation.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/rotor_transition.hpp"
#include "gyro/status.hpp"

namespace gyro {
template struct RotorTransition<float>;
template struct RotorTransition<double>;
template Status make_transition<float>(const RotorParameters<float>&, float, RotorTransition<float>&);
template Status make_transition<double>(const RotorParameters<double>&, double,
                                        RotorTransition<double>&);
template Status nutation_amplitude<float>(const RotorParameters<float>&, const Vector2<float>&,
                                          const Vector2<float>&, Vector2<float>&);
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

#include "gyro/noise.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {
template class NoiseStream<float>;
template class NoiseStream<double>;
template class SimulatedGyro<float>;
template class SimulatedGyro<double>;
}  // namespace gyro
