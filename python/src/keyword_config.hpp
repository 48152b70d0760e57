// A configuration struct's fields by name, for configuring from keyword arguments or a dict
// and for reading the configuration back as a dict. An unknown key or a value of the wrong
// kind is a gyro.ConfigError naming the field (the values themselves are checked by the
// C++ configure(), whose refusal names the field too).
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "errors.hpp"
#include "scenario.hpp"  // sil::edit_distance

namespace gyro::python {

namespace py = pybind11;

template <typename C>
class FieldTable {
 public:
  struct Field {
    std::string name;
    std::function<void(C&, py::handle, const std::string&)> set;  // path: the field's name for messages
    std::function<py::object(const C&)> get;
  };

  // A number (float or double member).
  template <typename T>
  FieldTable& number(const char* name, T C::*member) {
    fields_.push_back({name, [member](C& c, py::handle v, const std::string& path) { c.*member = to_number<T>(v, path); },
                       [member](const C& c) -> py::object { return py::float_(static_cast<double>(c.*member)); }});
    return *this;
  }
  // A boolean.
  FieldTable& boolean(const char* name, bool C::*member) {
    fields_.push_back({name,
                       [member](C& c, py::handle v, const std::string& path) {
                         if (!py::isinstance<py::bool_>(v)) raise_config_error(path, "expected true or false");
                         c.*member = v.cast<bool>();
                       },
                       [member](const C& c) -> py::object { return py::bool_(c.*member); }});
    return *this;
  }
  // A fixed-size vector (Eigen) given as a sequence of numbers.
  template <typename T, int N>
  FieldTable& vector(const char* name, Eigen::Matrix<T, N, 1> C::*member) {
    fields_.push_back({name,
                       [member](C& c, py::handle v, const std::string& path) {
                         if (!py::isinstance<py::sequence>(v) || py::isinstance<py::str>(v) || py::len(v) != N) {
                           raise_config_error(path, "expected " + std::to_string(N) + " numbers");
                         }
                         const py::sequence s = py::reinterpret_borrow<py::sequence>(v);
                         for (int i = 0; i < N; ++i) {
                           (c.*member)(i) = to_number<T>(s[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
                         }
                       },
                       [member](const C& c) -> py::object {
                         py::list l;
                         for (int i = 0; i < N; ++i) l.append(static_cast<double>((c.*member)(i)));
                         return l;
                       }});
    return *this;
  }
  // An enumeration given by name.
  template <typename E>
  FieldTable& choice(const char* name, E C::*member, std::vector<std::pair<std::string, E>> names) {
    fields_.push_back({name,
                       [member, names](C& c, py::handle v, const std::string& path) {
                         std::string all;
                         if (py::isinstance<py::str>(v)) {
                           const std::string s = v.cast<std::string>();
                           for (const auto& [n, e] : names) {
                             if (n == s) {
                               c.*member = e;
                               return;
                             }
                           }
                         }
                         for (const auto& [n, e] : names) all += (all.empty() ? "" : ", ") + n;
                         raise_config_error(path, "expected one of " + all);
                       },
                       [member, names](const C& c) -> py::object {
                         for (const auto& [n, e] : names) {
                           if (c.*member == e) return py::str(n);
                         }
                         return py::none();
                       }});
    return *this;
  }
  // A nested struct given as a dict.
  template <typename S>
  FieldTable& nested(const char* name, S C::*member, FieldTable<S> table) {
    auto shared = std::make_shared<FieldTable<S>>(std::move(table));
    fields_.push_back({name,
                       [member, shared](C& c, py::handle v, const std::string& path) {
                         if (!py::isinstance<py::dict>(v)) raise_config_error(path, "expected a dict");
                         shared->apply(c.*member, py::reinterpret_borrow<py::dict>(v), path + ".");
                       },
                       [member, shared](const C& c) -> py::object { return shared->to_dict(c.*member); }});
    return *this;
  }

  // Sets every key of `values` on `c`; `prefix` is prepended to the field names in messages.
  void apply(C& c, const py::dict& values, const std::string& prefix = "") const {
    for (const auto& [key, value] : values) {
      const std::string k = py::str(key).cast<std::string>();
      const Field* f = find(k);
      if (f == nullptr) raise_config_error(prefix + k, "unknown field" + suggestion(k));
      f->set(c, value, prefix + k);
    }
  }
  [[nodiscard]] py::dict to_dict(const C& c) const {
    py::dict d;
    for (const Field& f : fields_) d[py::str(f.name)] = f.get(c);
    return d;
  }
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const Field& f : fields_) n.push_back(f.name);
    return n;
  }

 private:
  template <typename T>
  static T to_number(py::handle v, const std::string& path) {
    if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v)) raise_config_error(path, "expected a number");
    const double d = PyFloat_AsDouble(v.ptr());
    if (PyErr_Occurred() != nullptr) {
      PyErr_Clear();
      raise_config_error(path, "expected a number");
    }
    return static_cast<T>(d);
  }
  [[nodiscard]] const Field* find(const std::string& k) const {
    for (const Field& f : fields_) {
      if (f.name == k) return &f;
    }
    return nullptr;
  }
  // " (did you mean x?)" for the closest known name sharing most of its characters.
  [[nodiscard]] std::string suggestion(const std::string& k) const {
    std::string best;
    std::size_t best_d = k.size() / 3 + 1;
    for (const Field& f : fields_) {
      const std::size_t d = sil::edit_distance(k, f.name);
      if (d <= best_d) {
        best_d = d;
        best = f.name;
      }
    }
    return best.empty() ? "" : " (did you mean " + best + "?)";
  }

  std::vector<Field> fields_;
};

// The keyword arguments merged over the dict `config` (None: empty).
inline py::dict merged_config(const py::object& config, const py::kwargs& fields, const char* who) {
  py::dict d;
  if (!config.is_none()) {
    if (!py::isinstance<py::dict>(config)) {
      raise_python("ConfigError", py::make_tuple(std::string(who) + ": config must be a dict", "config", Status::kOutOfRange));
    }
    for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(config)) d[k] = v;
  }
  for (const auto& [k, v] : fields) d[k] = v;
  return d;
}

}  // namespace gyro::python
