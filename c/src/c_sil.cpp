// gyro.h's SIL run (host only): a scenario run by gyro_sil's loop (apps/sil_runner.hpp) into
// columns in memory (apps/sil_columns.hpp). Every exception is caught here and becomes a status
// and a message: none crosses into C.
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <optional>
#include <string>

#include "gyro/gyro.h"
#include "scenario.hpp"
#include "sil_columns.hpp"
#include "sil_runner.hpp"

struct gyro_sil_result {
  gyro::sil::ColumnRecorder columns;
  gyro::sil::RunSummary summary;
};

namespace {

using gyro::sil::SilColumn;

// The status, with its message and field copied into the caller's buffers (cut to fit). No
// allocation: it also reports running out of memory.
int refuse(gyro_sil_error* error, int status, const char* message, const char* field = "") noexcept {
  if (error != nullptr) {
    std::snprintf(error->message, sizeof error->message, "%s", message);
    std::snprintf(error->field, sizeof error->field, "%s", field);
  }
  return status;
}

int run(const std::optional<std::string>& path, const char* text, const gyro_sil_options* options,
        gyro_sil_result** result, gyro_sil_error* error) noexcept {
  if (result == nullptr || (!path && text == nullptr)) return refuse(error, GYRO_NULL_ARGUMENT, "a required pointer is NULL");
  *result = nullptr;
  try {
    std::optional<gyro::sil::Precision> precision;
    std::optional<std::uint64_t> ticks;
    std::uint64_t max_bytes = gyro::sil::kDefaultMaxOutputBytes;
    if (options != nullptr) {
      if (options->precision != nullptr) {
        precision = gyro::sil::parse_precision(options->precision);
        if (!precision) {
          const std::string why =
              std::string("precision: expected \"float\" or \"double\", got \"") + options->precision + "\"";
          return refuse(error, GYRO_OUT_OF_RANGE, why.c_str(), "precision");
        }
      }
      if (options->ticks != 0) ticks = options->ticks;
      if (options->max_output_bytes != 0) max_bytes = options->max_output_bytes;
    }
    const std::string name = path ? *path : std::string("<text>");
    const gyro::sil::Scenario s = gyro::sil::prepare_scenario(path, text != nullptr ? text : "", name, precision, ticks);
    const std::string too_large = gyro::sil::output_bound_refusal(s, max_bytes, "max_output_bytes");
    if (!too_large.empty()) return refuse(error, GYRO_RUN_ERROR, too_large.c_str(), "max_output_bytes");
    auto* r = new gyro_sil_result;
    gyro::sil::RunOptions run_options;
    run_options.progress = false;
    try {
      r->summary = gyro::sil::run_scenario(s, r->columns, run_options);
    } catch (...) {
      delete r;
      throw;
    }
    *result = r;
    return refuse(error, GYRO_OK, "");
  } catch (const gyro::sil::ScenarioError& e) {
    return refuse(error, GYRO_SCENARIO_ERROR, e.what(), e.field().c_str());
  } catch (const gyro::sil::RunError& e) {
    return refuse(error, GYRO_RUN_ERROR, e.what());
  } catch (const std::bad_alloc&) {
    return refuse(error, GYRO_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return refuse(error, GYRO_INTERNAL_ERROR, e.what());
  } catch (...) {
    return refuse(error, GYRO_INTERNAL_ERROR, "unknown exception");
  }
}

const SilColumn* column(const gyro_sil_result* r, std::size_t i) noexcept {
  return r != nullptr && i < r->columns.columns().size() ? &r->columns.columns()[i] : nullptr;
}

}  // namespace

extern "C" {

int gyro_sil_run_file(const char* path, const gyro_sil_options* options, gyro_sil_result** result,
                      gyro_sil_error* error) {
  if (path == nullptr) return refuse(error, GYRO_NULL_ARGUMENT, "a required pointer is NULL");
  try {
    return run(std::string(path), nullptr, options, result, error);
  } catch (...) {  // the path's copy
    return refuse(error, GYRO_OUT_OF_MEMORY, "out of memory");
  }
}

int gyro_sil_run_text(const char* json, const gyro_sil_options* options, gyro_sil_result** result,
                      gyro_sil_error* error) {
  return run(std::nullopt, json, options, result, error);
}

void gyro_sil_free(gyro_sil_result* r) { delete r; }

size_t gyro_sil_rows(const gyro_sil_result* r) { return r != nullptr ? r->columns.rows() : 0; }
size_t gyro_sil_columns(const gyro_sil_result* r) { return r != nullptr ? r->columns.columns().size() : 0; }

const char* gyro_sil_column_name(const gyro_sil_result* r, size_t i) {
  const SilColumn* c = column(r, i);
  return c != nullptr ? c->name.data() : nullptr;  // csv_columns() are NUL-terminated literals
}

int gyro_sil_column_kind(const gyro_sil_result* r, size_t i) {
  const SilColumn* c = column(r, i);
  if (c == nullptr) return -1;
  switch (c->kind) {
    case SilColumn::Kind::kNumbers: return GYRO_SIL_NUMBERS;
    case SilColumn::Kind::kIntegers: return GYRO_SIL_INTEGERS;
    case SilColumn::Kind::kNames: return GYRO_SIL_NAMES;
  }
  return -1;
}

const double* gyro_sil_numbers(const gyro_sil_result* r, size_t i) {
  const SilColumn* c = column(r, i);
  return c != nullptr && c->kind == SilColumn::Kind::kNumbers ? c->numbers.data() : nullptr;
}
const uint64_t* gyro_sil_integers(const gyro_sil_result* r, size_t i) {
  const SilColumn* c = column(r, i);
  return c != nullptr && c->kind == SilColumn::Kind::kIntegers ? c->integers.data() : nullptr;
}
const char* gyro_sil_name(const gyro_sil_result* r, size_t i, size_t row) {
  const SilColumn* c = column(r, i);
  return c != nullptr && c->kind == SilColumn::Kind::kNames && row < c->names.size() ? c->names[row] : nullptr;
}

void gyro_sil_get_summary(const gyro_sil_result* r, gyro_sil_summary* out) {
  if (r == nullptr || out == nullptr) return;
  const gyro::sil::RunSummary& s = r->summary;
  *out = gyro_sil_summary{s.ticks,         s.rows,           gyro::sil::to_string(s.precision), gyro::enum_name_or(s.final_mode, "unknown"),
                          s.flags_seen,    s.refused_steps,  s.nonfinite_values,   s.gimbal_stop_hits,
                          s.max_abs_gimbal_rad};
}

uint32_t gyro_sil_counter(const gyro_sil_result* r, size_t bit) {
  return r != nullptr && bit < r->summary.counters.size() ? r->summary.counters[bit] : 0u;
}

size_t gyro_component_flag_count(void) { return static_cast<size_t>(gyro::kComponentFlagCount); }
const char* gyro_component_flag_name(size_t bit) {
  return bit < static_cast<size_t>(gyro::kComponentFlagCount) ? gyro::flag_name(static_cast<int>(bit)) : nullptr;
}

}  // extern "C"
