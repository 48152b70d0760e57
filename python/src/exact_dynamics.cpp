// The exact rotor dynamics (gyro/rotor_transition.hpp) on one state or on a batch of states:
// a state is (theta, psi, theta', psi'), a torque (T1, T2); a batch is an (n, 4) array of
// states with an (n, 2) array of torques (or one torque for all). The loops run in C++ with
// the GIL released; every row goes through the same gyro::advance as a single state.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
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

// One step of every row; `step(i, state)` returns the row's Status. `rows` nullopt: a single
// state (shape (4,)); else a batch of that many rows, none included (an empty (0, 4) batch
// gives an empty (0, 4) result and an empty status array).
template <typename T, typename Step>
py::object run_rows(const CArray<T>& states, std::optional<py::ssize_t> batch, bool return_status, const char* what,
                    Step&& step) {
  if (!batch) {  // a single state
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
  const py::ssize_t rows = *batch;
  py::array_t<T> out({rows, py::ssize_t{4}});
  py::array_t<std::uint8_t> status(rows);
  BatchOutcome outcome;
  if (rows > 0) {
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

std::string rows_text(std::optional<py::ssize_t> rows) {
  return rows ? std::to_string(*rows) + " states" : "a single state";
}

template <typename T>
Torques<T> torques_for(const CArray<T>& torque, std::optional<py::ssize_t> rows) {
  const std::optional<py::ssize_t> n = batch_rows<T>(torque, 2, "torque");
  if (n && !rows) {
    throw py::value_error("torque: a batch of " + std::to_string(*n) + " torques needs a batch of states, got " +
                          rows_text(rows));
  }
  if (n && *n != *rows) {
    throw py::value_error("torque: expected shape (2,) or (" + std::to_string(*rows) + ", 2), one row per state, got " +
                          std::to_string(*n) + " rows");
  }
  return {torque.data(), n.has_value()};
}

template <typename T>
py::object advance_any(const RotorTransition<T>& tr, const py::object& state_arg, const py::object& torque_arg,
                       bool return_status) {
  const CArray<T> state = real_array_of<T>(state_arg, "state");
  const CArray<T> torque = real_array_of<T>(torque_arg, "torque");
  const std::optional<py::ssize_t> rows = batch_rows<T>(state, 4, "state");
  const Torques<T> tq = torques_for(torque, rows);
  return run_rows<T>(state, rows, return_status, "advance",
                     [&](py::ssize_t i, RotorState<T>& s) { return advance(tr, tq.at(i), s); });
}

// Parameters and steps per row: `params` (n, 4) of (J1, J2, f, H) and `dt` (n,), or one of each.
template <typename T>
py::object propagate_any(const py::object& params, const py::object& dt, const py::object& state_arg,
                         const py::object& torque_arg, bool return_status) {
  const CArray<T> state = real_array_of<T>(state_arg, "state");
  const CArray<T> torque = real_array_of<T>(torque_arg, "torque");
  const std::optional<py::ssize_t> rows = batch_rows<T>(state, 4, "state");
  const Torques<T> tq = torques_for(torque, rows);
  std::vector<RotorParameters<T>> prm;
  bool prm_per_row = false;
  if (py::isinstance<RotorParameters<double>>(params)) {
    prm.push_back(cast_params<T>(params.cast<RotorParameters<double>>()));
  } else {
    const CArray<T> p = real_array_of<T>(params, "params");
    const std::optional<py::ssize_t> n = batch_rows<T>(p, 4, "params");
    if (!n || !rows || *n != *rows) {
      throw py::value_error("params: expected a RotorParameters or an (n, 4) array for a batch of n states, "
                            "got shape " +
                            array_detail::shape_text(p) + " for " + rows_text(rows));
    }
    prm_per_row = true;
    for (py::ssize_t i = 0; i < *n; ++i) {
      const T* r = p.data() + 4 * i;
      prm.push_back({r[0], r[1], r[2], r[3]});
    }
  }
  const CArray<T> steps = real_array_of<T>(dt, "dt");
  const bool dt_per_row = steps.ndim() == 1 && rows && steps.shape(0) == *rows;
  if (!(steps.ndim() == 0 || dt_per_row)) {
    throw py::value_error("dt: expected a number or shape (" + (rows ? std::to_string(*rows) : std::string("n")) +
                          ",), one per state, got shape " + array_detail::shape_text(steps) + " for " +
                          rows_text(rows));
  }
  const T* dts = steps.data();
  return run_rows<T>(state, rows, return_status, "propagate", [&](py::ssize_t i, RotorState<T>& s) {
    const std::size_t k = static_cast<std::size_t>(i);
    return propagate(prm[prm_per_row ? k : 0], dts[dt_per_row ? k : 0], tq.at(i), s);
  });
}

// RotorParameters' fields as properties whose setter checks the value's kind.
inline constexpr char kPitchInertia[] = "pitch_inertia";
inline constexpr char kYawInertia[] = "yaw_inertia";
inline constexpr char kFriction[] = "friction";
inline constexpr char kAngularMomentum[] = "angular_momentum";
template <double RotorParameters<double>::*M>
double get_field(const RotorParameters<double>& p) {
  return p.*M;
}
template <double RotorParameters<double>::*M, const char* Name>
void set_field(RotorParameters<double>& p, const py::object& v) {
  p.*M = real_scalar(v, Name);
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
      [](const RotorTransition<T>& tr, const py::object& state, const py::object& torque, bool return_status) {
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
      .def(py::init([](const py::object& pitch_inertia, const py::object& yaw_inertia, const py::object& friction,
                       const py::object& angular_momentum) {
             return RotorParameters<double>{real_scalar(pitch_inertia, "pitch_inertia"),
                                            real_scalar(yaw_inertia, "yaw_inertia"), real_scalar(friction, "friction"),
                                            real_scalar(angular_momentum, "angular_momentum")};
           }),
           py::arg("pitch_inertia"), py::arg("yaw_inertia"), py::arg("friction") = 0.0,
           py::arg("angular_momentum") = 0.0,
           "J1 (pitch gimbal axis), J2 (yaw gimbal axis), viscous friction f, spin angular momentum H.")
      .def_static(
          "from_spin",
          [](const py::object& pitch_inertia, const py::object& yaw_inertia, const py::object& friction,
             const py::object& spin_hz, const py::object& spin_inertia) {
            return RotorParameters<double>{
                real_scalar(pitch_inertia, "pitch_inertia"), real_scalar(yaw_inertia, "yaw_inertia"),
                real_scalar(friction, "friction"),
                angular_momentum(real_scalar(spin_hz, "spin_hz"), real_scalar(spin_inertia, "spin_inertia"))};
          },
          py::arg("pitch_inertia"), py::arg("yaw_inertia"), py::arg("friction"), py::arg("spin_hz"),
          py::arg("spin_inertia"), "The parameters with H = 2 pi spin_hz J0.")
      .def_property("pitch_inertia", &get_field<&RotorParameters<double>::pitch_inertia>,
                    &set_field<&RotorParameters<double>::pitch_inertia, kPitchInertia>, "J1")
      .def_property("yaw_inertia", &get_field<&RotorParameters<double>::yaw_inertia>,
                    &set_field<&RotorParameters<double>::yaw_inertia, kYawInertia>, "J2")
      .def_property("friction", &get_field<&RotorParameters<double>::friction>,
                    &set_field<&RotorParameters<double>::friction, kFriction>, "f")
      .def_property("angular_momentum", &get_field<&RotorParameters<double>::angular_momentum>,
                    &set_field<&RotorParameters<double>::angular_momentum, kAngularMomentum>, "H")
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
      [](const RotorParameters<double>& p, const py::object& dt_arg, const py::object& dtype) -> py::object {
        if (wants_float(dtype)) {
          const float dt = real_scalar<float>(dt_arg, "dt");
          RotorTransition<float> tr;
          raise_if_failed(make_transition(cast_params<float>(p), dt, tr), "make_transition");
          return py::cast(tr);
        }
        const double dt = real_scalar(dt_arg, "dt");
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
        if (is_float32(state)) return propagate_any<float>(params, dt, state, torque, return_status);
        return propagate_any<double>(params, dt, state, torque, return_status);
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
      [](const RotorParameters<double>& p, const py::object& torque_arg) {
        const Eigen::Vector2d torque = real_matrix<Eigen::Vector2d>(torque_arg, "torque");
        Eigen::Vector2d r;
        raise_if_failed(steady_precession_rate(p, torque, r), "steady_precession_rate");
        return to_array(r);
      },
      py::arg("params"), py::arg("torque"),
      "The steady precession (theta', psi') under a constant torque (report eq 11, k5 and k6).");

  m.def(
      "angular_momentum",
      [](const py::object& spin_hz, const py::object& spin_inertia) {
        return angular_momentum(real_scalar(spin_hz, "spin_hz"), real_scalar(spin_inertia, "spin_inertia"));
      },
      py::arg("spin_hz"), py::arg("spin_inertia"), "H = 2 pi spin_hz J0.");
}

}  // namespace gyro::python
