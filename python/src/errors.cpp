#include "errors.hpp"

#include "bindings.hpp"

namespace py = pybind11;

namespace gyro::python {

void raise_python(const char* name, const py::tuple& args) {
  const py::object cls = py::module_::import("gyro.errors").attr(name);
  const py::object exc = cls(*args);
  PyErr_SetObject(cls.ptr(), exc.ptr());
  throw py::error_already_set();
}

void raise_config_error(const std::string& field, const std::string& reason, Status s) {
  raise_python("ConfigError", py::make_tuple(field + ": " + reason, field, s));
}

void raise_if_refused(const ConfigCheck& c, const char* who) {
  if (c.ok()) return;
  const std::string field = c.field != nullptr ? c.field : "(unnamed)";
  raise_python("ConfigError",
               py::make_tuple(std::string(who) + ": " + field + ": " + to_string(c.status), field, c.status));
}

void raise_if_failed(Status s, const std::string& what, bool ignored_ok) {
  if (s == Status::kOk || (ignored_ok && s == Status::kInputIgnored)) return;
  raise_python("StatusError", py::make_tuple(what + ": " + to_string(s), s));
}

void bind_errors(py::module_& m) {
  py::enum_<Status>(m, "Status", "Status values of every fallible call (gyro/status.hpp).")
      .value("OK", Status::kOk)
      .value("NON_FINITE_INPUT", Status::kNonFiniteInput)
      .value("NON_POSITIVE_INERTIA", Status::kNonPositiveInertia)
      .value("NEGATIVE_FRICTION", Status::kNegativeFriction)
      .value("NEGATIVE_ANGULAR_MOMENTUM", Status::kNegativeAngularMomentum)
      .value("NON_POSITIVE_STEP", Status::kNonPositiveStep)
      .value("NO_STEADY_STATE", Status::kNoSteadyState)
      .value("OUT_OF_RANGE", Status::kOutOfRange)
      .value("NUMERICAL_OVERFLOW", Status::kNumericalOverflow)
      .value("NOT_CONFIGURED", Status::kNotConfigured)
      .value("INVALID_ROTATION", Status::kInvalidRotation)
      .value("WRONG_MODE", Status::kWrongMode)
      .value("INPUT_IGNORED", Status::kInputIgnored);
  m.def(
      "status_text", [](Status s) { return std::string(to_string(s)); }, py::arg("status"),
      "The description of a Status (\"non-finite input\", ...).");
}

}  // namespace gyro::python
