// Ctrl-C in the long calls (run_sil, run_campaign), which compute with the GIL released: the
// computing thread takes the GIL back now and then and runs Python's signal handlers; when one
// raises (KeyboardInterrupt), the call unwinds with Interrupted and the binding re-raises the
// Python exception left set (py::error_already_set).
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>

namespace gyro::python {

// Thrown out of a computation when a signal handler raised; the Python error is set.
struct Interrupted {};

// How often a long call checks for signals: a tick or a collection of finished runs takes the
// GIL at most this often.
inline constexpr std::chrono::milliseconds kSignalCheckPeriod{20};

// Whether a Python signal handler raised (its exception is then set). Called without the GIL;
// takes it for the check.
inline bool python_signal_raised() {
  const pybind11::gil_scoped_acquire gil;
  return PyErr_CheckSignals() != 0;
}

}  // namespace gyro::python
