// The pieces of the Python module _gyro, each binding one part of gyro (module.cpp calls them).
#pragma once

#include <pybind11/pybind11.h>

namespace gyro::python {

void bind_errors(pybind11::module_& m);          // Status and the exception helpers' enums
void bind_exact_dynamics(pybind11::module_& m);  // make_transition, advance, propagate
void bind_gyro_model(pybind11::module_& m);      // GyroModel, GyroModelF32
void bind_gimbal_plant(pybind11::module_& m);    // GimbalPlant, GimbalPlantF32
void bind_examples(pybind11::module_& m);        // the example gyros' configurations (gyro.examples)
void bind_flight_loop(pybind11::module_& m);     // SimulatedGyro, GyroComponent, SilLoop (and F32)
void bind_sil_run(pybind11::module_& m);         // run_sil
void bind_campaign_run(pybind11::module_& m);    // run_campaign

}  // namespace gyro::python
