// Refusals of the exception-free C++ as Python exceptions (gyro/errors.py): a ConfigCheck
// becomes ConfigError naming its field, any other Status a StatusError. The C++ below stays
// exception-free; only the binding layer raises.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "gyro/gyro_model.hpp"

namespace gyro::python {

// Raises gyro.ConfigError(message, field, status) when `c` is a refusal; `who` prefixes the
// message ("GyroModel.configure").
void raise_if_refused(const ConfigCheck& c, const char* who);
// The same with the field named `field` (as the caller's input names it).
void raise_if_refused(const ConfigCheck& c, const char* who, const std::string& field);
// Raises gyro.StatusError(message, status) unless `s` is kOk (or kInputIgnored when
// `ignored_ok`).
void raise_if_failed(Status s, const std::string& what, bool ignored_ok = false);
// Raises gyro.ConfigError for a field given by the caller (unknown key, wrong type).
[[noreturn]] void raise_config_error(const std::string& field, const std::string& reason, Status s = Status::kOutOfRange);
// Raises the exception class `name` of gyro.errors, built from `args`.
[[noreturn]] void raise_python(const char* name, const pybind11::tuple& args);

}  // namespace gyro::python
