// The nonlinear two-axis gimbal plant of the SIL stub (gyro/gimbal_plant.hpp): GimbalPlant in
// float64, GimbalPlantF32 in float32. Configured from keyword arguments or a dict (the fields
// of GimbalPlantConfig) and the tick, started, stepped one tick at a time.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <sstream>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "keyword_config.hpp"
#include "errors.hpp"
#include "gyro/gimbal_plant.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

// What a refused step names: the torque or the body's motion beyond the plant's envelope, with
// the value and the bound (the plant itself returns only kOutOfRange).
template <typename T>
std::string step_refusal(const GimbalPlantConfig<T>& c, const Vector2<T>& torque, const BodyState<T>& end) {
  std::ostringstream why;
  why.precision(6);
  why << "GimbalPlant.step";
  const T largest = torque.cwiseAbs().maxCoeff();
  if (largest > c.max_torque) {
    why << " (torque (" << torque(0) << ", " << torque(1) << ") is beyond max_torque " << c.max_torque
        << ": the torquers cannot drive it)";
  } else if (end.rate_rad_s.norm() > c.max_body_rate_rad_s) {
    why << " (body_rate of norm " << end.rate_rad_s.norm() << " is beyond max_body_rate_rad_s "
        << c.max_body_rate_rad_s << ")";
  } else if (end.specific_force.norm() > c.max_specific_force) {
    why << " (specific_force of norm " << end.specific_force.norm() << " is beyond max_specific_force "
        << c.max_specific_force << ")";
  }
  return why.str();
}

// The plant and the body's motion at its last tick (the start of the next step).
template <typename T>
struct PlantHandle {
  GimbalPlant<T> plant;
  BodyState<T> body;
};

template <typename T>
void configure_plant(PlantHandle<T>& h, T tick_s, const py::object& config, const py::kwargs& fields) {
  GimbalPlantConfig<T> c{};
  apply_fields(c, merged_config(config, fields, "GimbalPlant"));
  raise_if_refused(h.plant.configure(c, tick_s), "GimbalPlant.configure");
}

template <typename T>
BodyState<T> body_of(const Vector3<T>& rate, const Vector3<T>& force) {
  BodyState<T> b;
  b.rate_rad_s = rate;
  b.specific_force = force;
  return b;
}

template <typename T>
void bind_plant(py::module_& m, const char* name, const char* doc) {
  using H = PlantHandle<T>;
  using V2 = Vector2<T>;
  using V3 = Vector3<T>;
  py::class_<H>(m, name, doc)
      .def(py::init([](const py::object& tick_s, const py::object& config, const py::kwargs& fields) {
             H h;
             configure_plant(h, real_scalar<T>(tick_s, "tick_s"), config, fields);
             return h;
           }),
           py::arg("tick_s"), py::arg("config") = py::none(),
           "Configures for ticks of tick_s from a dict and/or keyword arguments (the fields of\n"
           "GimbalPlantConfig: spin_inertia, rotor_transverse_inertia, inner_gimbal_inertia (3 numbers),\n"
           "..., spin_drive='motor'|'free', torquer_axes='gimbal'|'gyro', the envelope max_*). A refusal\n"
           "raises gyro.ConfigError naming the field (tick_s included).")
      .def(
          "configure",
          [](H& h, const py::object& tick_s, const py::object& config, const py::kwargs& fields) {
            configure_plant(h, real_scalar<T>(tick_s, "tick_s"), config, fields);
          },
          py::arg("tick_s"), py::arg("config") = py::none(),
           "Configures again (as the constructor); the plant waits for start().")
      .def(
          "start",
          [](H& h, const py::object& angle_arg, const py::object& rate_arg, const py::object& spin_hz_arg,
             const py::object& body_rate, const py::object& force) {
            const V2 angle = matrix_or_zero<V2>(angle_arg, "gimbal_angle");
            const V2 rate = matrix_or_zero<V2>(rate_arg, "gimbal_rate");
            const T spin_hz = real_scalar<T>(spin_hz_arg, "spin_hz");
            const BodyState<T> b =
                body_of(matrix_or_zero<V3>(body_rate, "body_rate"), matrix_or_zero<V3>(force, "specific_force"));
            raise_if_failed(h.plant.start({angle, rate, spin_hz}, b), "GimbalPlant.start");
            h.body = b;
          },
          py::arg("gimbal_angle") = py::none(), py::arg("gimbal_rate") = py::none(), py::kw_only(),
          py::arg("spin_hz"), py::arg("body_rate") = py::none(), py::arg("specific_force") = py::none(),
          "Sets the joint angles (pitch, yaw) and rates relative to the carriers, the spin relative to the\n"
          "inner gimbal (Hz) and the body's rate (p, q, r) and specific force at t0. Raises gyro.StatusError.")
      .def(
          "step",
          [](H& h, const py::object& torque_arg, const py::object& body_rate_arg, const py::object& force_arg) {
            const V2 torque = real_matrix<V2>(torque_arg, "torque");
            const std::optional<V3> body_rate = optional_matrix<V3>(body_rate_arg, "body_rate");
            const std::optional<V3> force = optional_matrix<V3>(force_arg, "specific_force");
            const BodyState<T> end = body_of(body_rate ? *body_rate : h.body.rate_rad_s,
                                             force ? *force : h.body.specific_force);
            const Status stepped = h.plant.step(torque, h.body, end);
            if (stepped != Status::kOk) raise_if_failed(stepped, step_refusal(h.plant.config(), torque, end));
            h.body = end;
          },
          py::arg("torque"), py::kw_only(), py::arg("body_rate") = py::none(), py::arg("specific_force") = py::none(),
          "One tick with the torques (T1 inner/pitch, T2 outer/yaw) held; the body's rate and specific\n"
          "force go linearly from the last tick's to the given ones (unchanged if None). A refusal raises\n"
          "gyro.StatusError and changes nothing.")
      .def_property_readonly(
          "gimbal_angle", [](const H& h) { return to_array(V2(h.plant.gimbal_angle_rad())); },
          "Joint angles (pitch, yaw) rad.")
      .def_property_readonly(
          "gimbal_rate", [](const H& h) { return to_array(V2(h.plant.gimbal_rate_rad_s())); },
          "Joint rates (pitch, yaw) rad/s relative to the carriers.")
      .def_property_readonly(
          "spin_rate", [](const H& h) { return h.plant.spin_rate_rad_s(); }, "Spin relative to the inner gimbal (rad/s).")
      .def_property_readonly(
          "twist", [](const H& h) { return h.plant.joint_state().twist_rad; }, "Rotor twist angle (rad, wrapped).")
      .def_property_readonly("cone", [](const H& h) { return h.plant.cone_rad(); }, "Spin axis to body x (rad).")
      .def_property_readonly(
          "spin_axis_body", [](const H& h) { return to_array(V3(h.plant.spin_axis_body())); },
          "The spin axis in body axes (unit vector).")
      .def_property_readonly(
          "angular_momentum_body", [](const H& h) { return to_array(V3(h.plant.angular_momentum_body())); },
          "Angular momentum of rotor and gimbals about the gimbal centre, body axes.")
      .def_property_readonly(
          "rotor_angular_momentum_body", [](const H& h) { return to_array(V3(h.plant.rotor_angular_momentum_body())); },
          "The rotor's angular momentum, body axes.")
      .def_property_readonly("kinetic_energy", [](const H& h) { return h.plant.kinetic_energy(); },
                             "Kinetic energy of rotor and gimbals.")
      .def_property_readonly(
          "work",
          [](const H& h) {
            const GimbalWork<T>& w = h.plant.work();
            py::dict d;
            d["torquer"] = w.torquer;
            d["friction"] = w.friction;
            d["spin"] = w.spin;
            d["unbalance"] = w.unbalance;
            return d;
          },
          "Work done on the joints since start(), by source (dict).")
      .def_property_readonly("motor_torque", [](const H& h) { return h.plant.motor_torque(); },
                             "The last tick's mean spin-motor torque.")
      .def_property_readonly("motor_saturated", [](const H& h) { return h.plant.motor_saturated(); },
                             "Whether the motor hit its limit in the last tick.")
      .def_property_readonly("in_contact", [](const H& h) { return h.plant.in_contact(); },
                             "Whether the gimbal touched its stop in the last tick.")
      .def_property_readonly("substeps", [](const H& h) { return h.plant.substeps(); },
                             "Runge-Kutta sub-steps per tick, fixed by configure().")
      .def_property_readonly("tick_s", [](const H& h) { return h.plant.tick_s(); }, "The tick (s).")
      .def_property_readonly("started", [](const H& h) { return h.plant.started(); }, "Whether start() has run.")
      .def_property_readonly(
          "config", [](const H& h) { return fields_to_dict(h.plant.config()); },
          "The configuration as a dict.")
      .def_property_readonly_static(
          "dtype", [](const py::object&) { return py::dtype::of<T>(); }, "The scalar type: float64 or float32.")
      .def_property_readonly_static(
          "config_fields", [](const py::object&) { return field_names<GimbalPlantConfig<T>>(); }, "The configuration's keys.");
}

}  // namespace

void bind_gimbal_plant(py::module_& m) {
  bind_plant<double>(m, "GimbalPlant", "The nonlinear two-axis gimbal plant of the SIL stub, float64.");
  bind_plant<float>(m, "GimbalPlantF32", "The nonlinear two-axis gimbal plant of the SIL stub, float32.");
}

}  // namespace gyro::python
