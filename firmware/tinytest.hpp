// tinytest.hpp: the firmware's self-checking test runner. No heap, no exceptions, no
// stdio: tests register themselves statically and run in definition order, across all
// test files linked into the image. Prints one line per failed check and per failed test
// and closes with the line
//   N passed, N failed
// run_all() returns non-zero on any failure; the startup code turns main's return value
// into the emulator's exit status.
//
//   #include "tinytest.hpp"
//   TT_TEST(rotor_holds_steady_precession) {
//     TT_CHECK(status == gyro::Status::kOk);
//     TT_NEAR(rate(0), expected, 1e-6);
//   }
#pragma once

#include <cmath>

#include "fw_io.hpp"

namespace tt {

struct Case {
  const char* name;
  void (*fn)();
  Case* next;
};
struct Registry {
  Case* head = nullptr;
  Case* tail = nullptr;
  int failed_checks = 0;
};
inline Registry& reg() noexcept {
  static Registry r;  // constant-initialised: no guard, no constructor call
  return r;
}
struct Reg {
  explicit Reg(Case* c) noexcept {
    Registry& r = reg();
    (r.tail != nullptr ? r.tail->next : r.head) = c;  // keep definition order
    r.tail = c;
  }
};

inline void fail_check(const char* file, int line) noexcept {
  ++reg().failed_checks;
  gyro_fw::Line() << file << ':' << line << ": ";
}

inline int run_all() noexcept {
  int passed = 0, failed = 0;
  for (Case* c = reg().head; c != nullptr; c = c->next) {
    reg().failed_checks = 0;
    c->fn();
    if (reg().failed_checks == 0) {
      ++passed;
    } else {
      ++failed;
      gyro_fw::Line() << "FAILED: " << c->name << '\n';
    }
  }
  gyro_fw::Line() << passed << " passed, " << failed << " failed\n";
  return failed == 0 ? 0 : 1;
}

}  // namespace tt

#define TT_TEST(name)                                                 \
  static void tt_fn_##name();                                         \
  static tt::Case tt_case_##name{#name, tt_fn_##name, nullptr};      \
  static const tt::Reg tt_reg_##name{&tt_case_##name};                \
  static void tt_fn_##name()

#define TT_CHECK(cond)                                                \
  do {                                                                \
    if (!(cond)) {                                                    \
      tt::fail_check(__FILE__, __LINE__);                             \
      gyro_fw::Line() << "CHECK(" #cond ") failed\n";                 \
    }                                                                 \
  } while (0)

// |a - b| <= tol, compared in double (exact for float and double operands).
#define TT_NEAR(a, b, tol)                                                          \
  do {                                                                              \
    const double tt_a_ = static_cast<double>(a), tt_b_ = static_cast<double>(b);    \
    if (!(std::fabs(tt_a_ - tt_b_) <= static_cast<double>(tol))) {                  \
      tt::fail_check(__FILE__, __LINE__);                                           \
      gyro_fw::Line() << "NEAR(" #a ", " #b ") failed: " << tt_a_ << " vs " << tt_b_ \
                      << '\n';                                                      \
    }                                                                               \
  } while (0)

// In exactly one file of an image: #define TT_MAIN before including (firmware/tests/main.cpp).
#ifdef TT_MAIN
int main() { return tt::run_all(); }
#endif
