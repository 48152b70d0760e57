// GyroModel (gyro/gyro_model.hpp), the report's subroutine GYRO as a class: GyroModel in
// float64, GyroModelF32 in float32. Configured from keyword arguments or a dict (the fields of
// GyroModelConfig; errors as a nested dict {"pitch": {...}, "yaw": {...}}), uncaged, stepped.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "keyword_config.hpp"
#include "errors.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

template <typename T>
void configure_model(GyroModel<T>& g, const py::object& config, const py::kwargs& fields) {
  GyroModelConfig<T> c{};
  apply_fields(c, merged_config(config, fields, "GyroModel"));
  raise_if_refused(g.configure(c), "GyroModel.configure");
}

template <typename T>
Matrix3<T> attitude_or_identity(const std::optional<Matrix3<T>>& r) {
  return r ? *r : Matrix3<T>(Matrix3<T>::Identity());
}

// The optional inputs default to None (not to zero vectors): a default converted from NumPy
// on every call would cost more than the step itself.
// Every argument goes through arrays.hpp's checks (real numbers only, shapes), named.
template <typename T>
GyroStepInput<T> step_input(const py::object& dt, const py::object& spin_hz, const py::object& r,
                            const py::object& accel, const py::object& body_rate) {
  GyroStepInput<T> in;
  in.dt_s = real_scalar<T>(dt, "dt");
  in.R_earth_to_body = attitude_or_identity(optional_matrix<Matrix3<T>>(r, "R_earth_to_body"));
  if (const auto a = optional_matrix<Vector2<T>>(accel, "body_accel")) in.body_accel = *a;
  in.spin_hz = real_scalar<T>(spin_hz, "spin_hz");
  if (const auto b = optional_matrix<Vector3<T>>(body_rate, "body_rate")) in.body_rate_rad_s = *b;
  return in;
}

template <typename T>
void bind_model(py::module_& m, const char* name, const char* doc) {
  using G = GyroModel<T>;
  using V2 = Vector2<T>;
  using V3 = Vector3<T>;
  using M3 = std::optional<Matrix3<T>>;
  const std::string who(name);
  py::class_<G>(m, name, doc)
      .def(py::init([](const py::object& config, const py::kwargs& fields) {
             G g;
             configure_model(g, config, fields);
             return g;
           }),
           py::arg("config") = py::none(),
           "Configures from a dict and/or keyword arguments (the fields of GyroModelConfig: pitch_inertia,\n"
           "yaw_inertia, spin_inertia, friction, gimbal_cone_limit_rad, max_pitch_rate_rad_s,\n"
           "max_yaw_rate_rad_s, ..., errors={'pitch': {...}, 'yaw': {...}}, torquer_axes='gyro'|'gimbal').\n"
           "Keyword arguments override the dict. A refusal raises gyro.ConfigError naming the field.")
      .def("configure", &configure_model<T>, py::arg("config") = py::none(),
           "Configures again (as the constructor); leaves the gyro caged. Raises gyro.ConfigError.")
      .def(
          "uncage",
          [](G& g, const py::object& r, const py::object& body_rate, const py::object& offset) {
            const M3 rm = optional_matrix<Matrix3<T>>(r, "R_earth_to_body");
            const V2 br = matrix_or_zero<V2>(body_rate, "body_rate");
            const V2 off = matrix_or_zero<V2>(offset, "offset");
            raise_if_failed(g.uncage(attitude_or_identity(rm), br, off), "GyroModel.uncage");
          },
          py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(), py::arg("offset") = py::none(),
          "Uncages: rates from the body's (pitch, yaw) rates, attitude from the body's (identity if None)\n"
          "plus a small (pitch, yaw) offset. Raises gyro.StatusError.")
      .def(
          "uncage_on_gimbal",
          [](G& g, const py::object& r, const py::object& body_rate, const py::object& gimbal) {
            const M3 rm = optional_matrix<Matrix3<T>>(r, "R_earth_to_body");
            const V3 br = matrix_or_zero<V3>(body_rate, "body_rate");
            const V2 gm = matrix_or_zero<V2>(gimbal, "gimbal");
            raise_if_failed(g.uncage_on_gimbal(attitude_or_identity(rm), br, gm), "GyroModel.uncage_on_gimbal");
          },
          py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(), py::arg("gimbal") = py::none(),
          "Uncages at the gimbal angles (pitch, yaw), the gimbals at rest relative to the body (p, q, r).")
      .def(
          "step_torque",
          [](G& g, const py::object& dt, const py::object& torque, const py::object& spin_hz, const py::object& r,
             const py::object& accel, const py::object& body_rate) {
            const GyroStepInput<T> in = step_input<T>(dt, spin_hz, r, accel, body_rate);
            raise_if_failed(g.step_torque(in, real_matrix<V2>(torque, "torque")), "GyroModel.step_torque");
          },
          py::arg("dt"), py::arg("torque"), py::kw_only(), py::arg("spin_hz"), py::arg("R_earth_to_body") = py::none(),
          py::arg("body_accel") = py::none(), py::arg("body_rate") = py::none(),
          "One step of dt with the torquer torques (T1, T2) held: gyro axes, or (inner, outer) with\n"
          "torquer_axes='gimbal'. R_earth_to_body is the body attitude at the END of the step (identity\n"
          "if None), body_accel (lateral, normal) in the units of gravity, body_rate (p, q, r) for the\n"
          "gimbal torquer axes (zero if None). A refusal raises gyro.StatusError and leaves the state unchanged.")
      .def(
          "step_slew",
          [](G& g, const py::object& dt, const py::object& slew, const py::object& spin_hz, const py::object& r,
             const py::object& accel, const py::object& body_rate) {
            const GyroStepInput<T> in = step_input<T>(dt, spin_hz, r, accel, body_rate);
            raise_if_failed(g.step_slew(in, real_matrix<V2>(slew, "slew_rate")), "GyroModel.step_slew");
          },
          py::arg("dt"), py::arg("slew_rate"), py::kw_only(), py::arg("spin_hz"),
          py::arg("R_earth_to_body") = py::none(), py::arg("body_accel") = py::none(),
          py::arg("body_rate") = py::none(),
          "One step with the report's command: slew rates (pitch, yaw) limited per axis and turned into\n"
          "torque for a frictionless gyro. Otherwise as step_torque().")
      .def(
          "correct_attitude",
          [](G& g, const py::object& angle, const py::object& r) {
            const V2 a = real_matrix<V2>(angle, "angle");
            const M3 rm = optional_matrix<Matrix3<T>>(r, "R_earth_to_body");
            raise_if_failed(g.correct_attitude(a, attitude_or_identity(rm)), "GyroModel.correct_attitude");
          },
          py::arg("angle"), py::arg("R_earth_to_body") = py::none(),
          "Turns the gyro by small (pitch, yaw) angles about its own axes (an estimator's correction).")
      .def_property_readonly(
          "rate", [](const G& g) { return to_array(V2(g.rate_rad_s())); }, "(theta', psi') rad/s, gyro axes.")
      .def_property_readonly(
          "rate_on_gimbal", [](const G& g) { return to_array(V2(g.rate_on_gimbal_rad_s())); },
          "The spin axis's inertial rate on the inner gimbal axes (rad/s).")
      .def_property_readonly(
          "gimbal", [](const G& g) { return to_array(V2(g.gimbal_pitch_rad(), g.gimbal_yaw_rad())); },
          "Gimbal angles (pitch, yaw) rad at the end of the last step.")
      .def_property_readonly("gimbal_pitch", &G::gimbal_pitch_rad, "Gimbal pitch angle (rad).")
      .def_property_readonly("gimbal_yaw", &G::gimbal_yaw_rad, "Gimbal yaw angle (rad).")
      .def_property_readonly("gimbal_cone", &G::gimbal_cone_rad, "Angle between spin axis and body x (rad).")
      .def_property_readonly(
          "isaf_angle", [](const G& g) { return to_array(V2(g.isaf_angle_rad())); },
          "The last step's angles (theta, psi) in the inertial small-angle frame (rad).")
      .def_property_readonly(
          "nutation_amplitude", [](const G& g) { return to_array(V2(g.nutation_amplitude_rad())); },
          "The nutation's amplitude per axis after the last step (rad).")
      .def_property_readonly(
          "applied_torque", [](const G& g) { return to_array(V2(g.applied_torque())); },
          "The torque on the rotor over the last step (with the error sources).")
      .def_property_readonly(
          "attitude",
          [](const G& g) {
            const Quaternion<T>& q = g.attitude_gyro_to_earth();
            return to_array(Eigen::Matrix<T, 4, 1>(q.w(), q.x(), q.y(), q.z()));
          },
          "Quaternion (w, x, y, z), gyro to earth.")
      .def_property_readonly(
          "R_earth_to_gyro", [](const G& g) { return to_array(Matrix3<T>(g.R_earth_to_gyro())); },
          "Rotation matrix earth to gyro axes (3x3).")
      .def_property_readonly("flags", &G::flags, "Flag word: bit 0 gimbal limit, bit 1 small angle exceeded.")
      .def_property_readonly("gimbal_limit_exceeded", &G::gimbal_limit_exceeded, "Flag bit 0.")
      .def_property_readonly("small_angle_exceeded", &G::small_angle_exceeded, "Flag bit 1.")
      .def_property_readonly("uncaged", &G::uncaged, "Whether uncage() has run since configure().")
      .def_property_readonly(
          "config", [](const G& g) { return fields_to_dict(g.config()); },
          "The configuration as a dict (the constructor's keys).")
      .def_property_readonly_static(
          "dtype", [](const py::object&) { return py::dtype::of<T>(); }, "The scalar type: float64 or float32.")
      .def_property_readonly_static(
          "config_fields", [](const py::object&) { return field_names<GyroModelConfig<T>>(); }, "The configuration's keys.")
      .def("__repr__", [who](const G& g) {
        return who + "(uncaged=" + (g.uncaged() ? "True" : "False") + ")";
      });
}

}  // namespace

void bind_gyro_model(py::module_& m) {
  bind_model<double>(m, "GyroModel", "The report's gyro model (subroutine GYRO), float64.");
  bind_model<float>(m, "GyroModelF32", "The report's gyro model (subroutine GYRO), float32.");
  m.attr("FLAG_GIMBAL_LIMIT") = static_cast<unsigned>(kFlagGimbalLimit);
  m.attr("FLAG_SMALL_ANGLE") = static_cast<unsigned>(kFlagSmallAngle);
  // The report's sample run as gyro_report_sample drives it, for gyro.report_sample.
  using Sample = ReportSample<double>;
  py::dict sample;
  sample["config"] = fields_to_dict(Sample::config());
  sample["spin_hz"] = Sample::kSpinHz;
  sample["body_rates"] = py::make_tuple(Sample::kBodyPitchRate, Sample::kBodyYawRate);
  const Vector2<double> slew = Sample::slew_command();
  sample["slew"] = py::make_tuple(slew(0), slew(1));
  sample["steps"] = Sample::kSteps;
  sample["initg_step"] = Sample::initg_step();
  m.attr("_report_sample") = sample;
  m.def(
      "frame_rotation_y",
      [](const py::object& a) { return to_array(Eigen::Matrix3d(frame_rotation_y(real_scalar(a, "angle")))); },
      py::arg("angle"),
      "The passive rotation of a body turning by `angle` about its own y axis: R_new = R_y(angle) @ R_old.");
  m.def(
      "frame_rotation_z",
      [](const py::object& a) { return to_array(Eigen::Matrix3d(frame_rotation_z(real_scalar(a, "angle")))); },
      py::arg("angle"),
      "The passive rotation of a body turning by `angle` about its own z axis: R_new = R_z(angle) @ R_old.");
}

}  // namespace gyro::python
