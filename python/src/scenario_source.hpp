// A scenario or campaign handed in from Python: a file path (str or os.PathLike) or a dict,
// which goes through json.dumps and the same parser as a file.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace gyro::python {

namespace py = pybind11;

struct DocumentSource {
  std::optional<std::string> path;  // a file
  std::string text;                 // a dict's JSON text (path empty)
  std::string name;                 // for messages: the path, or "<dict>"
};

inline DocumentSource document_source(const py::object& source, const char* what) {
  const py::module_ os = py::module_::import("os");
  if (py::isinstance<py::str>(source) || py::isinstance(source, os.attr("PathLike"))) {
    const std::string p = os.attr("fspath")(source).cast<std::string>();
    return {p, "", p};
  }
  if (py::isinstance<py::dict>(source)) {
    const std::string text = py::module_::import("json").attr("dumps")(source).cast<std::string>();
    return {std::nullopt, text, "<dict>"};
  }
  throw py::type_error(std::string(what) + " must be a file path or a dict");
}

}  // namespace gyro::python
