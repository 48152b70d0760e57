// The flight component, the simulated gyro and the SIL loop (gyro/gyro_component.hpp,
// gyro/simulated_gyro.hpp, gyro/sil_loop.hpp), so that a simulation author writes the loop
// with a body and a guidance of their own: SimulatedGyro, GyroComponent, SilLoop in float64,
// the same with F32 in float32.
//
// Their keywords are a scenario's (docs/scenarios.md): SimulatedGyro takes the keys of a
// scenario's "gyro" section, GyroComponent those of its "component" section, each with the
// tick; they go through gyro_sil's own parser (the same defaults, the same refusals, naming the
// field as the scenario does, "rotor.pitch_inertia"), then the C++ configure().
//
// The simulation side raises on a refusal (gyro.StatusError); the flight component returns
// its Status, as on the target: activate() and step() return a gyro.Status.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/sil_contract.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "keyword_config.hpp"
#include "scenario.hpp"
#include "strict_json.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

// A dict of keywords as a scenario section's JSON (NumPy arrays and scalars as lists and
// numbers): what the scenario parser reads.
nlohmann::json section_json(const py::dict& fields) {
  const py::cpp_function plain([](const py::object& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("not a JSON value: " + py::repr(o).cast<std::string>());
  });
  const std::string text = py::module_::import("json").attr("dumps")(fields, py::arg("default") = plain).cast<std::string>();
  return sil::parse_strict_json(text, sil::kMaxJsonDepth, sil::KeyJoin::kQuoted);
}

// A scenario's refusal as gyro.ConfigError: "who: field: reason", the field as named.
[[noreturn]] void raise_scenario_refusal(const sil::ScenarioError& e, const char* who) {
  raise_python("ConfigError", py::make_tuple(std::string(who) + ": " + e.field() + ": " + e.reason(), e.field(),
                                             Status::kOutOfRange));
}

// The keywords read as a scenario section by `parse` (sil::parse_gyro_section, ...); a refusal
// as gyro.ConfigError.
using SectionParser = sil::Scenario (*)(const nlohmann::json&, double, const std::string&, const std::string&);
sil::Scenario parse_section(SectionParser parse, double tick_s, const py::object& config, const py::kwargs& fields,
                            const char* who) {
  try {
    return parse(section_json(merged_config(config, fields, who)), tick_s, who, "");
  } catch (const sil::ScenarioError& e) {
    raise_scenario_refusal(e, who);
  } catch (const sil::JsonRefusal& e) {
    raise_config_error(e.field(), e.reason());
  }
}

// The field a stub's configure() named, as the gyro section names it ("limits.gimbal_stop_rad").
std::string gyro_key(const sil::Scenario& s, const char* field) {
  const std::string path = sil::gyro_field_path(s, field != nullptr ? field : "(unnamed)");
  const std::string prefix = "gyro.";
  return path.rfind(prefix, 0) == 0 ? path.substr(prefix.size()) : path;
}

template <typename T, template <class> class Config>
Config<T> in_precision(const Config<double>& d) {
  Config<T> out;
  cast_fields(d, out);
  return out;
}

// The simulated gyro with the configuration's scenario form kept (for the component's
// pairing rule and the names of refusals).
template <typename T>
struct StubHandle {
  SimulatedGyro<T> stub;
  sil::Scenario scenario;  // its gyro section
};

template <typename T>
void configure_stub(StubHandle<T>& h, double tick_s, const py::object& config, const py::kwargs& fields) {
  sil::Scenario s = parse_section(&sil::parse_gyro_section, tick_s, config, fields, "SimulatedGyro");
  const ConfigCheck c = h.stub.configure(in_precision<T>(s.gyro));
  if (!c.ok()) raise_if_refused(c, "SimulatedGyro.configure", gyro_key(s, c.field));
  h.scenario = std::move(s);
}

// The component over a stub it keeps alive (the Python object holds the reference).
template <typename T>
struct ComponentHandle {
  explicit ComponentHandle(StubHandle<T>& s) : stub(&s), component(s.stub) {}
  StubHandle<T>* stub;
  GyroComponent<T> component;
};

template <typename T>
void configure_component(ComponentHandle<T>& h, double tick_s, const py::object& config, const py::kwargs& fields) {
  const sil::Scenario s = parse_section(&sil::parse_component_section, tick_s, config, fields, "GyroComponent");
  const GyroComponentConfig<T> c = in_precision<T>(s.component);
  raise_if_refused(h.component.configure(c), "GyroComponent.configure");
  // The rules between the component and the hardware it flies (the stub's configuration).
  ConfigCheckList<32> pair;
  check_against_hardware(h.stub->stub.config(), c, pair);
  if (!pair.empty()) raise_if_refused(pair[0], "GyroComponent.configure (against the SimulatedGyro's hardware)");
}

template <typename T>
BodySample<T> body_sample(const py::object& r, const py::object& rate, const py::object& force) {
  BodySample<T> b;
  if (const auto m = optional_matrix<Matrix3<T>>(r, "R_earth_to_body")) b.R_earth_to_body = *m;
  b.rate_rad_s = matrix_or_zero<Vector3<T>>(rate, "body_rate");
  b.specific_force = matrix_or_zero<Vector3<T>>(force, "specific_force");
  return b;
}

ModeRequest request_of(const py::object& v) {
  if (v.is_none()) return ModeRequest::kNone;
  ModeRequest r{};
  if (py::isinstance<py::str>(v) && enum_from_name(v.cast<std::string>(), r)) return r;
  throw py::value_error("request: expected None, 'none', 'cage' or 'uncage', got " + py::repr(v).cast<std::string>());
}

template <typename T>
GuidanceCommand<T> command_of(const py::object& request, const py::object& slew, const py::object& nav_valid) {
  GuidanceCommand<T> c;
  c.request = request_of(request);
  c.slew_rate_cmd_rad_s = matrix_or_zero<Vector2<T>>(slew, "slew_rate");
  if (!py::isinstance<py::bool_>(nav_valid)) throw py::type_error("nav_valid: expected True or False");
  c.nav_valid = nav_valid.cast<bool>();
  return c;
}

py::list flag_list(std::uint32_t flags) {
  py::list names;
  for (int b = 0; b < kComponentFlagCount; ++b) {
    if ((flags & (1u << static_cast<unsigned>(b))) != 0u) names.append(flag_name(b));
  }
  return names;
}

template <typename T>
py::dict telemetry_dict(const GyroTelemetry<T>& t) {
  py::dict d;
  d["tick"] = t.tick;
  d["mode"] = enum_name_or(t.mode, "?");
  d["flags"] = t.flags;
  d["flag_names"] = flag_list(t.flags);
  py::dict counters;
  for (int b = 0; b < kComponentFlagCount; ++b) counters[flag_name(b)] = t.counters[static_cast<std::size_t>(b)];
  d["counters"] = counters;
  d["gimbal_measured_rad"] = to_array(t.gimbal_measured_rad);
  d["gimbal_predicted_rad"] = to_array(t.gimbal_predicted_rad);
  d["residual_rad"] = to_array(t.residual_rad);
  const Quaternion<T>& q = t.attitude_gyro_to_earth;
  d["attitude_gyro_to_earth"] = to_array(Eigen::Matrix<T, 4, 1>(q.w(), q.x(), q.y(), q.z()));
  d["precession_rate_rad_s"] = to_array(t.precession_rate_rad_s);
  d["rate_cmd_rad_s"] = to_array(t.rate_cmd_rad_s);
  d["torque_cmd"] = to_array(t.torque_cmd);
  d["nutation_amplitude_rad"] = to_array(t.nutation_amplitude_rad);
  d["spin_hz"] = static_cast<double>(t.spin_hz);
  return d;
}

py::list fault_names(std::uint32_t bits) {
  py::list names;
  for (int k = 1; k < kFaultKindCount; ++k) {
    if ((bits & fault_bit(static_cast<FaultKind>(k))) != 0u) names.append(fault_kind_name(static_cast<FaultKind>(k)));
  }
  return names;
}

constexpr const char* kBodyDoc =
    "The body: R_earth_to_body (3x3, identity if None), body_rate (p, q, r) rad/s and specific_force\n"
    "(body axes, zero if None).";

template <typename T>
void bind_stub(py::module_& m, const char* name, const char* doc) {
  using H = StubHandle<T>;
  using V2 = Vector2<T>;
  py::class_<H, std::shared_ptr<H>>(m, name, doc)
      .def(py::init([](const py::object& tick_s, const py::object& config, const py::kwargs& fields) {
             auto h = std::make_shared<H>();
             configure_stub(*h, real_scalar<double>(tick_s, "tick_s"), config, fields);
             return h;
           }),
           py::arg("tick_s"), py::arg("config") = py::none(),
           "Configures for ticks of tick_s from a dict and/or keyword arguments: the keys of a scenario's\n"
           "\"gyro\" section (docs/scenarios.md: plant, rotor={...}, limits={...}, gimbal={...}, pickoff,\n"
           "torquer, gravity, errors, seed, faults=[...]), with its defaults. gyro.examples.seeker().gyro is\n"
           "one. A refusal raises gyro.ConfigError naming the field as the scenario does (rotor.spin_hz).")
      .def(
          "start",
          [](H& h, const py::object& r, const py::object& rate, const py::object& force) {
            raise_if_failed(h.stub.start(body_sample<T>(r, rate, force)), "SimulatedGyro.start");
          },
          py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(),
          py::arg("specific_force") = py::none(),
          (std::string("Power-up at tick 0, the gyro aligned with the body. ") + kBodyDoc + " Raises gyro.StatusError.")
              .c_str())
      .def(
          "advance",
          [](H& h, std::uint64_t tick, const py::object& r, const py::object& rate, const py::object& force) {
            raise_if_failed(h.stub.advance(tick, body_sample<T>(r, rate, force)), "SimulatedGyro.advance");
          },
          py::arg("tick"), py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(),
          py::arg("specific_force") = py::none(),
          (std::string("To tick (the previous + 1) with the torque last written held; samples the pickoffs. ") +
           kBodyDoc + " Raises gyro.StatusError.")
              .c_str())
      .def(
          "write_torquer",
          [](H& h, const py::object& torque) {
            const PortStatus s = h.stub.write_torquer(real_matrix<V2>(torque, "torque"));
            if (s != PortStatus::kOk) raise_if_failed(Status::kOutOfRange, "SimulatedGyro.write_torquer");
          },
          py::arg("torque"),
          "Latches a torque command (inner, outer) as the component's port does; the torquer's electronics\n"
          "saturate it (see applied_torque).")
      .def_property_readonly("gimbal_angle", [](const H& h) { return to_array(V2(h.stub.gimbal_angle_rad())); },
                             "The true gimbal angles (pitch, yaw) rad.")
      .def_property_readonly("spin_axis_rate", [](const H& h) { return to_array(V2(h.stub.spin_axis_rate_rad_s())); },
                             "The spin axis's true inertial rate on the inner gimbal axes (pitch, yaw) rad/s.")
      .def_property_readonly("cone", [](const H& h) { return static_cast<double>(h.stub.cone_rad()); },
                             "The true cone: spin axis to body x (rad).")
      .def_property_readonly("applied_torque", [](const H& h) { return to_array(V2(h.stub.applied_torque())); },
                             "The torque the torquers apply: the command after scale, saturation and faults.")
      .def_property_readonly("torque_command", [](const H& h) { return to_array(V2(h.stub.torque_command())); },
                             "The last torque command written.")
      .def_property_readonly("spin_hz", [](const H& h) { return static_cast<double>(h.stub.spin_hz()); },
                             "The true spin (Hz).")
      .def_property_readonly("at_gimbal_stop", [](const H& h) { return h.stub.at_gimbal_stop(); },
                             "Whether the gimbal was on its stop in the last advance().")
      .def_property_readonly("active_faults", [](const H& h) { return fault_names(h.stub.active_faults()); },
                             "The names of the faults active at the current tick.")
      .def_property_readonly("tick", [](const H& h) { return h.stub.tick(); }, "The current tick.")
      .def_property_readonly_static(
          "dtype", [](const py::object&) { return py::dtype::of<T>(); }, "The scalar type: float64 or float32.");
}

template <typename T>
void bind_component(py::module_& m, const char* name, const char* stub_name, const char* doc) {
  using H = ComponentHandle<T>;
  using S = StubHandle<T>;
  py::class_<H, std::shared_ptr<H>>(m, name, doc)
      .def(py::init([](const std::shared_ptr<S>& port, const py::object& tick_s, const py::object& config,
                       const py::kwargs& fields) {
             auto h = std::make_shared<H>(*port);
             configure_component(*h, real_scalar<double>(tick_s, "tick_s"), config, fields);
             return h;
           }),
           py::arg("port"), py::arg("tick_s"), py::arg("config") = py::none(), py::keep_alive<1, 2>(),
           (std::string("The flight component on the port `port` (a ") + stub_name +
            "), configured for ticks of tick_s from a dict\n"
            "and/or keyword arguments: the keys of a scenario's \"component\" section (docs/scenarios.md,\n"
            "GyroComponentConfig), with its defaults; gyro.examples.seeker().component is one. A refusal\n"
            "raises gyro.ConfigError naming the field, also for the rules against the port's hardware.")
               .c_str())
      .def(
          "configure",
          [](H& h, const py::object& tick_s, const py::object& config, const py::kwargs& fields) {
            configure_component(h, real_scalar<double>(tick_s, "tick_s"), config, fields);
          },
          py::arg("tick_s"), py::arg("config") = py::none(), "Configures again (as the constructor): idle.")
      .def("activate", [](H& h) { return h.component.activate(); }, "Idle -> caged. Returns a gyro.Status.")
      .def(
          "step",
          [](H& h, std::uint64_t tick, const py::object& request, const py::object& slew, const py::object& nav_valid,
             const py::object& r, const py::object& rate) {
            const GuidanceCommand<T> c = command_of<T>(request, slew, nav_valid);
            BodySample<T> b;
            if (const auto mr = optional_matrix<Matrix3<T>>(r, "R_earth_to_body")) b.R_earth_to_body = *mr;
            b.rate_rad_s = matrix_or_zero<Vector3<T>>(rate, "body_rate");
            return h.component.step(tick, guidance_input(c, b));
          },
          py::arg("tick"), py::kw_only(), py::arg("request") = py::none(), py::arg("slew_rate") = py::none(),
          py::arg("nav_valid") = true, py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(),
          "One tick: reads the pickoffs, runs the modes, monitors, estimator and torque law, writes the\n"
          "torquer. request None/'none'/'cage'/'uncage', slew_rate (pitch, yaw) rad/s, nav_valid, the body's\n"
          "attitude and rates from navigation. Returns a gyro.Status (OK, INPUT_IGNORED, ...).")
      .def_property_readonly("telemetry", [](const H& h) { return telemetry_dict(h.component.telemetry()); },
                             "This tick's telemetry as a dict (GyroTelemetry's members; flags also by name).")
      .def_property_readonly("mode", [](const H& h) { return std::string(enum_name_or(h.component.mode(), "?")); },
                             "'idle', 'caged', 'uncaging', 'free' or 'fault'.")
      .def_property_readonly("config", [](const H& h) { return fields_to_dict(h.component.config()); },
                             "The configuration as a dict.")
      .def_property_readonly_static(
          "dtype", [](const py::object&) { return py::dtype::of<T>(); }, "The scalar type: float64 or float32.");
}

// The loop over a stub and a component of the same precision, both kept alive.
template <typename T>
struct LoopHandle {
  LoopHandle(std::shared_ptr<StubHandle<T>> s, std::shared_ptr<ComponentHandle<T>> c)
      : stub(std::move(s)), component(std::move(c)), loop(stub->stub, component->component) {}
  std::shared_ptr<StubHandle<T>> stub;
  std::shared_ptr<ComponentHandle<T>> component;
  SilLoop<T, GyroComponent<T>> loop;
};

template <typename T>
void bind_loop(py::module_& m, const char* name, const char* doc) {
  using H = LoopHandle<T>;
  py::class_<H>(m, name, doc)
      .def(py::init([](const std::shared_ptr<StubHandle<T>>& stub, const std::shared_ptr<ComponentHandle<T>>& c) {
             if (c->stub != stub.get()) throw py::value_error("SilLoop: the component does not fly this SimulatedGyro");
             return std::make_unique<H>(stub, c);
           }),
           py::arg("stub"), py::arg("component"))
      .def(
          "start",
          [](H& h, const py::object& r, const py::object& rate, const py::object& force) {
            const SilStatus<Status> s = h.loop.start(body_sample<T>(r, rate, force));
            raise_if_failed(s.stub, "SilLoop.start: SimulatedGyro.start");
            return s.component;
          },
          py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(),
          py::arg("specific_force") = py::none(),
          (std::string("Tick 0: the stub powers up with the body, the component is activated; returns its\n"
                       "gyro.Status. ") + kBodyDoc).c_str())
      .def(
          "tick",
          [](H& h, std::uint64_t k, const py::object& r, const py::object& rate, const py::object& force,
             const py::object& request, const py::object& slew, const py::object& nav_valid) {
            const GuidanceCommand<T> c = command_of<T>(request, slew, nav_valid);
            const SilStatus<Status> s = h.loop.tick(k, body_sample<T>(r, rate, force), c);
            raise_if_failed(s.stub, "SilLoop.tick " + std::to_string(k) + ": SimulatedGyro.advance");
            return s.component;
          },
          py::arg("tick"), py::kw_only(), py::arg("R_earth_to_body") = py::none(), py::arg("body_rate") = py::none(),
          py::arg("specific_force") = py::none(), py::arg("request") = py::none(), py::arg("slew_rate") = py::none(),
          py::arg("nav_valid") = true,
          "Tick k: the stub advances to the body at k (not at k = 0), the component steps with the command\n"
          "and the body's attitude and rates; returns the component's gyro.Status. As gyro_sil's loop.")
      .def_property_readonly("stub", [](const H& h) { return h.stub; })
      .def_property_readonly("component", [](const H& h) { return h.component; });
}

}  // namespace

void bind_flight_loop(py::module_& m) {
  bind_stub<double>(m, "SimulatedGyro", "The simulated gyro hardware behind the port (the SIL stub), float64.");
  bind_stub<float>(m, "SimulatedGyroF32", "The simulated gyro hardware behind the port (the SIL stub), float32.");
  bind_component<double>(m, "GyroComponent", "SimulatedGyro", "The flight gyro component, float64.");
  bind_component<float>(m, "GyroComponentF32", "SimulatedGyroF32", "The flight gyro component, float32.");
  bind_loop<double>(m, "SilLoop", "The closed loop of gyro_sil: body -> SimulatedGyro -> GyroComponent, float64.");
  bind_loop<float>(m, "SilLoopF32", "The closed loop of gyro_sil, float32.");
}

}  // namespace gyro::python
