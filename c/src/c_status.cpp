// gyro.h's statuses, refusal messages and version. Flight part: no heap, no exceptions.
#include <cstddef>

#include "c_fields.hpp"
#include "gyro/config_check.hpp"
#include "gyro/status.hpp"

namespace {

using gyro::Status;

// gyro.h's first statuses are gyro::Status's values, in its order.
static_assert(GYRO_OK == static_cast<int>(Status::kOk) && GYRO_NON_FINITE_INPUT == static_cast<int>(Status::kNonFiniteInput) &&
                  GYRO_INVALID_ROTATION == static_cast<int>(Status::kInvalidRotation) &&
                  GYRO_INPUT_IGNORED == static_cast<int>(Status::kInputIgnored),
              "gyro.h's statuses follow gyro::Status");
static_assert(gyro::enum_names(Status{}).size() == GYRO_INPUT_IGNORED + 1, "a gyro.h status for every gyro::Status");

// The C API's own statuses, from GYRO_NULL_ARGUMENT on: name and text.
struct Own {
  const char* name;
  const char* text;
};
constexpr Own kOwn[] = {
    {"null_argument", "a required pointer is NULL"},
    {"storage_too_small", "the storage is smaller than the object's storage size"},
    {"unknown_field", "no configuration field (or choice) of that name"},
    {"scenario_error", "the scenario is refused"},
    {"run_error", "the run failed"},
    {"out_of_memory", "out of memory"},
    {"internal_error", "internal error of the gyro library"},
};
static_assert(sizeof(kOwn) / sizeof(Own) == GYRO_INTERNAL_ERROR - GYRO_NULL_ARGUMENT + 1, "a name for every own status");

const Own* own(int status) noexcept {
  if (status < GYRO_NULL_ARGUMENT || status > GYRO_INTERNAL_ERROR) return nullptr;
  return &kOwn[status - GYRO_NULL_ARGUMENT];
}

bool is_library_status(int status) noexcept {
  return status >= 0 && static_cast<std::size_t>(status) < gyro::enum_names(Status{}).size();
}

}  // namespace

extern "C" {

unsigned gyro_abi_version(void) { return GYRO_ABI_VERSION; }
const char* gyro_version_string(void) { return GYRO_VERSION_STRING; }

const char* gyro_status_text(int status) {
  if (is_library_status(status)) return gyro::to_string(static_cast<Status>(status));
  const Own* o = own(status);
  return o != nullptr ? o->text : "unknown status";
}

const char* gyro_status_name(int status) {
  if (is_library_status(status)) return gyro::enum_names(Status{})[static_cast<std::size_t>(status)];
  const Own* o = own(status);
  return o != nullptr ? o->name : "unknown";
}

int gyro_refusal_text(const gyro_refusal* refusal, char* buf, size_t n) {
  if (refusal == nullptr) return 0;
  gyro::ConfigCheck c;
  c.status = is_library_status(refusal->status) ? static_cast<Status>(refusal->status) : Status::kOutOfRange;
  c.field = refusal->field;
  c.value = refusal->value;
  c.bound = refusal->bound;
  c.relation = refusal->relation >= 0 && refusal->relation <= 3 ? static_cast<gyro::Relation>(refusal->relation)
                                                                 : gyro::Relation::kNone;
  c.bound_name = refusal->bound_name;
  c.rule = refusal->rule;
  if (c.ok() || refusal->field == nullptr) {
    if (buf != nullptr && n > 0) buf[0] = '\0';
    return 0;
  }
  return gyro::format_refusal(c, nullptr, buf, n);
}

}  // extern "C"
