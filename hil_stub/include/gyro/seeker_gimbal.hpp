// The seeker example (gyro/seeker_example.hpp) as a device for the gimbal plant: a rotor of
// J0 = 3e-5, A = 1.6e-5 kg m^2 (a disc with some axial length: J0 <= 2A) on gimbal rings of a
// few e-6 kg m^2, chosen so that the effective inertias at zero gimbal angles are the
// example's J1 = J2 = 2e-5 (pitch: Iy + A; yaw: Oz + Iz + A), with its friction 4e-4 N m s on
// each bearing and its 400 Hz spin held by a motor. The component's configuration stays
// valid for it; the model error left is what the plant is for.
#pragma once

#include "gyro/gimbal_plant_config.hpp"
#include "gyro/seeker_example.hpp"

namespace gyro {

template <typename T>
[[nodiscard]] GimbalPlantConfig<T> seeker_gimbal_config() noexcept {
  return SeekerExample<T>::gimbal();
}

}  // namespace gyro
