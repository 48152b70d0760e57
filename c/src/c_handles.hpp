// The opaque model handles of gyro.h: what each one holds (used by the storage and heap parts).
#pragma once

#include "gyro/gyro.h"
#include "gyro/gyro_model.hpp"

struct gyro_model_d {
  gyro::GyroModel<double> model;
};
struct gyro_model_f {
  gyro::GyroModel<float> model;
};
