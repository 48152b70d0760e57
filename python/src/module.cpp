// The extension module gyro._gyro; the package gyro (gyro/__init__.py) re-exports it.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_gyro, m) {
  m.doc() = "gyro: exact two-axis gimballed gyro dynamics, the gyro model, the gimbal plant, SIL runs and campaigns";
  gyro::python::bind_errors(m);
  gyro::python::bind_exact_dynamics(m);
  gyro::python::bind_gyro_model(m);
  gyro::python::bind_gimbal_plant(m);
  gyro::python::bind_flight_loop(m);
  gyro::python::bind_examples(m);
  gyro::python::bind_sil_run(m);
  gyro::python::bind_campaign_run(m);
}
