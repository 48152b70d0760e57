// A configuration struct's fields by name, for configuring from keyword arguments or a dict
// and for reading the configuration back as a dict: the struct's own field table
// (gyro/config_fields.hpp) walked, so a field added to the table is a keyword here too.
// An unknown key or a value of the wrong kind is a gyro.ConfigError naming the field (the
// values themselves are checked by the C++ configure(), whose refusal names the field too).
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "arrays.hpp"
#include "errors.hpp"
#include "gyro/config_fields.hpp"
#include "scenario.hpp"  // sil::edit_distance

namespace gyro::python {

namespace py = pybind11;

namespace keyword_detail {

template <typename M>
M to_number(py::handle v, const std::string& path) {
  // arrays.hpp's check of a real number (no bool, complex or str), as a ConfigError.
  try {
    return real_scalar<M>(v, path.c_str());
  } catch (const py::type_error& e) {
    raise_config_error(path, std::string(e.what()).substr(path.size() + 2));
  } catch (const py::value_error& e) {
    raise_config_error(path, std::string(e.what()).substr(path.size() + 2));
  }
}

template <typename M>
M to_count(py::handle v, const std::string& path) {
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v)) raise_config_error(path, "expected a whole number");
  const long long n = v.cast<long long>();
  if (n < 0 || static_cast<unsigned long long>(n) > static_cast<unsigned long long>(~M(0))) {
    raise_config_error(path, "expected a whole number from 0 to " + std::to_string(~M(0)));
  }
  return static_cast<M>(n);
}

template <class Config>
void apply(Config& c, const py::dict& values, const std::string& prefix);
template <class Config>
py::dict to_dict(const Config& c);

// One member set from a Python value, by the member's type.
template <typename M>
void set_member(M& m, py::handle v, const std::string& path) {
  if constexpr (std::is_same_v<M, bool>) {
    if (!py::isinstance<py::bool_>(v)) raise_config_error(path, "expected true or false");
    m = v.cast<bool>();
  } else if constexpr (std::is_floating_point_v<M>) {
    m = to_number<M>(v, path);
  } else if constexpr (std::is_integral_v<M>) {
    m = to_count<M>(v, path);
  } else if constexpr (kHasEnumNames<M>) {
    if (py::isinstance<py::str>(v) && enum_from_name(v.cast<std::string>(), m)) return;
    std::string all;
    for (const char* n : enum_names(M{})) all += (all.empty() ? "" : ", ") + std::string(n);
    raise_config_error(path, "expected one of " + all);
  } else if constexpr (kHasFieldTable<M>) {
    if (!py::isinstance<py::dict>(v)) raise_config_error(path, "expected a dict");
    apply(m, py::reinterpret_borrow<py::dict>(v), path + ".");
  } else {
    static_assert(std::is_base_of_v<Eigen::EigenBase<M>, M>, "a field type the keywords cannot take");
    constexpr int n = M::RowsAtCompileTime;
    if (!py::isinstance<py::sequence>(v) || py::isinstance<py::str>(v) || py::len(v) != static_cast<std::size_t>(n)) {
      raise_config_error(path, "expected " + std::to_string(n) + " numbers");
    }
    const py::sequence s = py::reinterpret_borrow<py::sequence>(v);
    for (int i = 0; i < n; ++i) {
      m(i) = to_number<typename M::Scalar>(s[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
    }
  }
}

// One member as a Python value.
template <typename M>
py::object get_member(const M& m) {
  if constexpr (std::is_same_v<M, bool>) {
    return py::bool_(m);
  } else if constexpr (std::is_floating_point_v<M>) {
    return py::float_(static_cast<double>(m));
  } else if constexpr (std::is_integral_v<M>) {
    return py::int_(m);
  } else if constexpr (kHasEnumNames<M>) {
    const char* name = enum_name(m);
    return name != nullptr ? py::object(py::str(name)) : py::object(py::none());
  } else if constexpr (kHasFieldTable<M>) {
    return to_dict(m);
  } else {
    py::list l;
    for (int i = 0; i < M::RowsAtCompileTime; ++i) l.append(static_cast<double>(m(i)));
    return l;
  }
}

template <class Config>
std::vector<std::string> names() {
  std::vector<std::string> n;
  const Config c{};
  visit_fields([&n](const Field& f, const auto&) { n.emplace_back(f.name); }, c);
  return n;
}

// " (did you mean x?)" for the closest known name sharing most of its characters.
inline std::string suggestion(const std::string& k, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_d = k.size() / 3 + 1;
  for (const std::string& n : known) {
    const std::size_t d = sil::edit_distance(k, n);
    if (d <= best_d) {
      best_d = d;
      best = n;
    }
  }
  return best.empty() ? "" : " (did you mean " + best + "?)";
}

template <class Config>
void apply(Config& c, const py::dict& values, const std::string& prefix) {
  for (const auto& [key, value] : values) {
    const std::string k = py::str(key).cast<std::string>();
    bool found = false;
    visit_fields(
        [&](const Field& f, auto& member) {
          if (found || k != f.name) return;
          found = true;
          set_member(member, value, prefix + k);
        },
        c);
    if (!found) raise_config_error(prefix + k, "unknown field" + suggestion(k, names<Config>()));
  }
}

template <class Config>
py::dict to_dict(const Config& c) {
  py::dict d;
  visit_fields([&d](const Field& f, const auto& member) { d[py::str(f.name)] = get_member(member); }, c);
  return d;
}

}  // namespace keyword_detail

// Sets every key of `values` on `c` (its field table's names; nested structs as dicts);
// `prefix` is prepended to the field names in messages.
template <class Config>
void apply_fields(Config& c, const py::dict& values, const std::string& prefix = "") {
  keyword_detail::apply(c, values, prefix);
}

// `c` as a dict of its field table's names (enumerations by name, nested structs as dicts).
template <class Config>
[[nodiscard]] py::dict fields_to_dict(const Config& c) {
  return keyword_detail::to_dict(c);
}

// The names of Config's fields, in its table's order.
template <class Config>
[[nodiscard]] std::vector<std::string> field_names() {
  return keyword_detail::names<Config>();
}

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
