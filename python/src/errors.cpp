#include "errors.hpp"

#include "bindings.hpp"

#include <cctype>
#include <cstddef>
#include <string>

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
  raise_if_refused(c, who, c.field != nullptr ? c.field : "(unnamed)");
}

void raise_if_refused(const ConfigCheck& c, const char* who, const std::string& field) {
  if (c.ok()) return;
  std::string reason = to_string(c.status);
  if (c.relation != Relation::kNone || c.rule != nullptr) {
    char buf[512];
    (void)format_refusal(c, nullptr, buf, sizeof buf);
    reason += std::string(" (") + buf + ")";  // the value, the bound and the rule
  }
  raise_python("ConfigError", py::make_tuple(std::string(who) + ": " + field + ": " + reason, field, c.status));
}

void raise_if_failed(Status s, const std::string& what, bool ignored_ok) {
  if (s == Status::kOk || (ignored_ok && s == Status::kInputIgnored)) return;
  raise_python("StatusError", py::make_tuple(what + ": " + to_string(s), s));
}

void bind_errors(py::module_& m) {
  // The names beside the enum (gyro/status.hpp), in Python's capitals: NON_FINITE_INPUT.
  py::enum_<Status> status(m, "Status", "Status values of every fallible call (gyro/status.hpp).");
  constexpr auto names = enum_names(Status{});
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::string name(names[i]);
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    status.value(name.c_str(), static_cast<Status>(i));
  }
  m.def(
      "status_text", [](Status s) { return std::string(to_string(s)); }, py::arg("status"),
      "The description of a Status (\"non-finite input\", ...).");
}

}  // namespace gyro::python
