// The exact rotor dynamics (gyro/rotor_transition.hpp) on one state or on a batch of states:
// a state is (theta, psi, theta', psi'), a torque (T1, T2); a batch is an (n, 4) array of
// states with an (n, 2) array of torques (or one torque for all). The loops run in C++ with
// the GIL released; every row goes through the same gyro::advance as a single state.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "gyro/rotor_transition.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

template <typename T>
RotorParameters<T> cast_params(const RotorParameters<double>& p) {
  return {static_cast<T>(p.pitch_inertia), static_cast<T>(p.yaw_inertia), static_cast<T>(p.friction),
          static_cast<T>(p.angular_momentum)};
}

template <typename T>
RotorState<T> state_of(const T* s) {
  RotorState<T> r;
  r.angle_rad = Vector2<T>(s[0], s[1]);
  r.rate_rad_s = Vector2<T>(s[2], s[3]);
  return r;
}
template <typename T>
void store(const RotorState<T>& r, T* out) {
  out[0] = r.angle_rad(0);
  out[1] = r.angle_rad(1);
  out[2] = r.rate_rad_s(0);
  out[3] = r.rate_rad_s(1);
}

// Rows refused keep their input state; the first refusal is reported (row, status).
struct BatchOutcome {
  py::ssize_t first_bad_row{-1};
  Status first_status{Status::kOk};
};

// One step of every row; `step(i, state)` returns the row's Status.
template <typename T, typename Step>
py::object run_rows(const CArray<T>& states, py::ssize_t rows, bool return_status, const char* what, Step&& step) {
  if (rows == 0) {  // a single state
    RotorState<T> s = state_of(states.data());
    const Status st = step(0, s);
    if (return_status) {
      py::array_t<T> out(4);
      store(st == Status::kOk ? s : state_of(states.data()), out.mutable_data());
      return py::make_tuple(out, st);
    }
    raise_if_failed(st, what);
    py::array_t<T> out(4);
    store(s, out.mutable_data());
    return out;
  }
  py::array_t<T> out({rows, py::ssize_t{4}});
  py::array_t<std::uint8_t> status(rows);
  BatchOutcome outcome;
  {
    const T* in = states.data();
    T* o = out.mutable_data();
    std::uint8_t* so = status.mutable_data();
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < rows; ++i) {
      RotorState<T> s = state_of(in + 4 * i);
      const Status st = step(i, s);
      if (st != Status::kOk) {
        s = state_of(in + 4 * i);
        if (outcome.first_bad_row < 0) outcome = {i, st};
      }
      store(s, o + 4 * i);
      so[i] = static_cast<std::uint8_t>(st);
    }
  }
  if (return_status) return py::make_tuple(out, status);
  if (outcome.first_bad_row >= 0) {
    raise_if_failed(outcome.first_status, std::string(what) + ", row " + std::to_string(outcome.first_bad_row));
  }
  return out;
}

// The torque of row i: one for all, or one per row.
template <typename T>
struct Torques {
  const T* data;
  bool per_row;
  [[nodiscard]] Vector2<T> at(py::ssize_t i) const {
    const T* t = per_row ? data + 2 * i : data;
    return Vector2<T>(t[0], t[1]);
  }
};

template <typename T>
Torques<T> torques_for(const CArray<T>& torque, py::ssize_t rows) {
  const py::ssize_t n = batch_rows<T>(torque, 2, "torque");
  if (n != 0 && n != rows) throw py::value_error("torque must have shape (2,) or one row per state");
  if (n != 0 && rows == 0) throw py::value_error("a batch of torques needs a batch of states");
  return {torque.data(), n != 0};
}

template <typename T>
py::object advance_any(const RotorTransition<T>& tr, const CArray<T>& state, const CArray<T>& torque,
                       bool return_status) {
  const py::ssize_t rows = batch_rows<T>(state, 4, "state");
  const Torques<T> tq = torques_for(torque, rows);
  return run_rows<T>(state, rows, return_status, "advance",
                     [&](py::ssize_t i, RotorState<T>& s) { return advance(tr, tq.at(i), s); });
}

// Parameters and steps per row: `params` (n, 4) of (J1, J2, f, H) and `dt` (n,), or one of each.
template <typename T>
py::object propagate_any(const py::object& params, const py::object& dt, const CArray<T>& state,
                         const CArray<T>& torque, bool return_status) {
  const py::ssize_t rows = batch_rows<T>(state, 4, "state");
  const Torques<T> tq = torques_for(torque, rows);
  std::vector<RotorParameters<T>> prm;
  if (py::isinstance<RotorParameters<double>>(params)) {
    prm.push_back(cast_params<T>(params.cast<RotorParameters<double>>()));
  } else {
    const CArray<T> p = py::cast<CArray<T>>(params);
    const py::ssize_t n = batch_rows<T>(p, 4, "params");
    if (n != rows || n == 0) throw py::value_error("params must be a RotorParameters or an (n, 4) array, n states");
    for (py::ssize_t i = 0; i < n; ++i) {
      const T* r = p.data() + 4 * i;
      prm.push_back({r[0], r[1], r[2], r[3]});
    }
  }
  const CArray<T> steps = py::cast<CArray<T>>(dt);
  if (!(steps.ndim() == 0 || (steps.ndim() == 1 && steps.shape(0) == (rows == 0 ? 1 : rows)))) {
    throw py::value_error("dt must be a number or one per state");
  }
  const bool dt_per_row = steps.ndim() == 1 && rows != 0;
  const bool prm_per_row = prm.size() > 1;
  const T* dts = steps.data();
  return run_rows<T>(state, rows, return_status, "propagate", [&](py::ssize_t i, RotorState<T>& s) {
    const std::size_t k = static_cast<std::size_t>(i);
    return propagate(prm[prm_per_row ? k : 0], dts[dt_per_row ? k : 0], tq.at(i), s);
  });
}

bool wants_float(const py::object& dtype) {
  const py::dtype d = py::dtype::from_args(dtype);
  if (d.is(py::dtype::of<float>()) || d.equal(py::dtype::of<float>())) return true;
  if (d.equal(py::dtype::of<double>())) return false;
  throw py::value_error("dtype must be float32 or float64");
}

bool is_float32(const py::object& a) {
  return py::isinstance<py::array>(a) && py::reinterpret_borrow<py::array>(a).dtype().equal(py::dtype::of<float>());
}

template <typename T>
void bind_transition(py::module_& m, const char* name, const char* doc) {
  py::class_<RotorTransition<T>>(m, name, doc)
      .def_property_readonly("dt", [](const RotorTransition<T>& t) { return t.dt_s; }, "The step (s).")
      .def_property_readonly(
          "rate_from_rate", [](const RotorTransition<T>& t) { return to_array(t.rate_from_rate); },
          "E0 = exp(A dt): rates at the end from rates at the start (2x2).")
      .def_property_readonly(
          "angle_from_rate", [](const RotorTransition<T>& t) { return to_array(t.angle_from_rate); },
          "E1 = integral of exp(A s) over the step: angles from rates (2x2).")
      .def_property_readonly(
          "rate_from_torque", [](const RotorTransition<T>& t) { return to_array(t.rate_from_torque); },
          "E1 J^-1: rates from the torque held over the step (2x2).")
      .def_property_readonly(
          "angle_from_torque", [](const RotorTransition<T>& t) { return to_array(t.angle_from_torque); },
          "E2 J^-1: angles from the torque held over the step (2x2).")
      .def_property_readonly(
          "dtype", [](const RotorTransition<T>&) { return py::dtype::of<T>(); }, "float64 or float32.")
      .def("__repr__", [name](const RotorTransition<T>& t) {
        return std::string(name) + "(dt=" + std::to_string(static_cast<double>(t.dt_s)) + ")";
      });
  m.def(
      "advance",
      [](const RotorTransition<T>& tr, const CArray<T>& state, const CArray<T>& torque, bool return_status) {
        return advance_any<T>(tr, state, torque, return_status);
      },
      py::arg("transition"), py::arg("state"), py::arg("torque"), py::kw_only(), py::arg("return_status") = false,
      "Advances a state (theta, psi, theta', psi') by the transition's step under a torque (T1, T2) held\n"
      "over it. state: shape (4,) or a batch (n, 4); torque: (2,) or (n, 2). Returns the new state(s) in\n"
      "the transition's dtype. A refusal (non-finite input, overflow) raises gyro.StatusError naming the\n"
      "first refused row; with return_status=True returns (states, status) instead, status a uint8 array\n"
      "of gyro.Status values per row (a Status for one state), refused rows left as they were.");
}

}  // namespace

void bind_exact_dynamics(py::module_& m) {
  py::class_<RotorParameters<double>>(m, "RotorParameters",
                                      "The linear rotor model's parameters (report eqs 1a, 1b), any consistent units.")
      .def(py::init([](double pitch_inertia, double yaw_inertia, double friction, double angular_momentum) {
             return RotorParameters<double>{pitch_inertia, yaw_inertia, friction, angular_momentum};
           }),
           py::arg("pitch_inertia"), py::arg("yaw_inertia"), py::arg("friction") = 0.0,
           py::arg("angular_momentum") = 0.0,
           "J1 (pitch gimbal axis), J2 (yaw gimbal axis), viscous friction f, spin angular momentum H.")
      .def_static(
          "from_spin",
          [](double pitch_inertia, double yaw_inertia, double friction, double spin_hz, double spin_inertia) {
            return RotorParameters<double>{pitch_inertia, yaw_inertia, friction,
                                           angular_momentum(spin_hz, spin_inertia)};
          },
          py::arg("pitch_inertia"), py::arg("yaw_inertia"), py::arg("friction"), py::arg("spin_hz"),
          py::arg("spin_inertia"), "The parameters with H = 2 pi spin_hz J0.")
      .def_readwrite("pitch_inertia", &RotorParameters<double>::pitch_inertia, "J1")
      .def_readwrite("yaw_inertia", &RotorParameters<double>::yaw_inertia, "J2")
      .def_readwrite("friction", &RotorParameters<double>::friction, "f")
      .def_readwrite("angular_momentum", &RotorParameters<double>::angular_momentum, "H")
      .def(
          "as_array",
          [](const RotorParameters<double>& p) {
            return to_array(Eigen::Vector4d(p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum));
          },
          "(J1, J2, f, H) as a float64 array: a row of propagate()'s per-state parameters.")
      .def("__repr__", [](const RotorParameters<double>& p) {
        return "RotorParameters(pitch_inertia=" + std::to_string(p.pitch_inertia) +
               ", yaw_inertia=" + std::to_string(p.yaw_inertia) + ", friction=" + std::to_string(p.friction) +
               ", angular_momentum=" + std::to_string(p.angular_momentum) + ")";
      });

  bind_transition<double>(m, "Transition", "The exact transition of the rotor over one step (float64).");
  bind_transition<float>(m, "TransitionF32", "The exact transition of the rotor over one step (float32).");

  m.def(
      "make_transition",
      [](const RotorParameters<double>& p, double dt, const py::object& dtype) -> py::object {
        if (wants_float(dtype)) {
          RotorTransition<float> tr;
          raise_if_failed(make_transition(cast_params<float>(p), static_cast<float>(dt), tr), "make_transition");
          return py::cast(tr);
        }
        RotorTransition<double> tr;
        raise_if_failed(make_transition(p, dt, tr), "make_transition");
        return py::cast(tr);
      },
      py::arg("params"), py::arg("dt"), py::arg("dtype") = py::dtype::of<double>(),
      "The exact transition of `params` over a step dt (closed form in every damping regime).\n"
      "dtype float64 gives a Transition, float32 a TransitionF32 (computed in float throughout).\n"
      "Raises gyro.StatusError for invalid parameters, dt <= 0 or a result not representable.");

  m.def(
      "propagate",
      [](const py::object& params, const py::object& dt, const py::object& state, const py::object& torque,
         bool return_status) -> py::object {
        if (is_float32(state)) {
          return propagate_any<float>(params, dt, py::cast<CArray<float>>(state), py::cast<CArray<float>>(torque),
                                      return_status);
        }
        return propagate_any<double>(params, dt, py::cast<CArray<double>>(state), py::cast<CArray<double>>(torque),
                                     return_status);
      },
      py::arg("params"), py::arg("dt"), py::arg("state"), py::arg("torque"), py::kw_only(),
      py::arg("return_status") = false,
      "make_transition then advance in one call, for parameters that change every step (spin-down).\n"
      "params: a RotorParameters, or for a batch an (n, 4) array of (J1, J2, f, H) rows; dt: a number or\n"
      "(n,). state (4,) or (n, 4), torque (2,) or (n, 2). A float32 state array computes in float32,\n"
      "anything else in float64. Refusals as advance().");

  m.def(
      "compute_modes",
      [](const RotorParameters<double>& p) {
        RotorModes<double> r;
        raise_if_failed(compute_modes(p, r), "compute_modes");
        const char* regimes[] = {"underdamped", "critical", "overdamped", "free"};
        py::dict d;
        d["alpha_1_s"] = r.alpha_1_s;
        d["beta_squared_1_s2"] = r.beta_squared_1_s2;
        d["beta_rad_s"] = r.beta_rad_s;
        d["natural_rate_rad_s"] = r.natural_rate_rad_s;
        d["slow_decay_rate_1_s"] = r.slow_decay_rate_1_s;
        d["fast_decay_rate_1_s"] = r.fast_decay_rate_1_s;
        d["nutation_hz"] = r.nutation_hz;
        d["regime"] = regimes[static_cast<int>(r.regime)];
        return d;
      },
      py::arg("params"),
      "The rotor's modes (report eq 11): alpha, beta, nutation_hz, decay rates and the damping regime, as a dict.");

  m.def(
      "steady_precession_rate",
      [](const RotorParameters<double>& p, const Eigen::Vector2d& torque) {
        Eigen::Vector2d r;
        raise_if_failed(steady_precession_rate(p, torque, r), "steady_precession_rate");
        return to_array(r);
      },
      py::arg("params"), py::arg("torque"),
      "The steady precession (theta', psi') under a constant torque (report eq 11, k5 and k6).");

  m.def(
      "angular_momentum", [](double spin_hz, double spin_inertia) { return angular_momentum(spin_hz, spin_inertia); },
      py::arg("spin_hz"), py::arg("spin_inertia"), "H = 2 pi spin_hz J0.");
}

}  // namespace gyro::python
