// The example gyros of examples/include/gyro/ as Python dicts, for gyro.examples: each
// configuration in the form its Python constructor takes (the C++ headers are the one
// definition; nothing is retyped in Python).
//   seeker: SeekerExample (gyro/seeker_example.hpp): the flight configuration and the stub's,
//           as a scenario's "component" and "gyro" sections; its gimbal plant and its rotor as
//           the GyroModel of the report's plant, as GimbalPlant's and GyroModel's keywords.
//   report: ReportSample (gyro/report_sample.hpp): the report's gyro as GyroModel's keywords.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include "bindings.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "keyword_config.hpp"
#include "scenario.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

py::object from_json(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

py::dict seeker() {
  using S = SeekerExample<double>;
  py::dict d;
  d["tick_s"] = S::kTick;
  d["gyro"] = from_json(sil::gyro_section(S::stub(), 0));
  d["component"] = from_json(sil::component_section(S::component()));
  d["gimbal_plant"] = fields_to_dict(S::gimbal());
  d["model"] = fields_to_dict(S::stub().gyro);
  d["spin_hz"] = S::kSpinHz;
  return d;
}

py::dict report() {
  using R = ReportSample<double>;
  py::dict d;
  d["tick_s"] = R::initg_step();
  d["model"] = fields_to_dict(R::config());
  d["spin_hz"] = R::kSpinHz;
  return d;
}

}  // namespace

void bind_examples(py::module_& m) {
  py::dict examples;
  examples["seeker"] = seeker();
  examples["report"] = report();
  m.attr("_examples") = examples;
}

}  // namespace gyro::python
