// Propagates the report's gyro for one step through the installed headers.
#include <gyro/rotor_transition.hpp>

int main() {
  const gyro::RotorParameters<double> rotor{2.25, 2.0, 5.0, gyro::angular_momentum(100.0, 3.0)};
  gyro::RotorState<double> state;
  state.rate_rad_s << 0.4, 0.3;
  const gyro::Status st = gyro::propagate(rotor, 1.0 / 2828.0, gyro::Vector2<double>(1.0, -1.0), state);
  return (st == gyro::Status::kOk && state.angle_rad.allFinite()) ? 0 : 1;
}
