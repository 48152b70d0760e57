// Instructions per step of the C API (gyro/gyro.h, through libgyro.so's PLT) against the same
// step called in C++ (inline, as a C++ caller has it): the exact step of one state, of a batch
// of states, and GyroModel's step, double and float, each in a loop with a compiler barrier
// per step so every step loads and stores its state. Counted by scripts/c-api-cost.sh with
// callgrind over two run lengths (the difference is the per-step cost).
//
//   gyro_bench_c_api <kind> <steps>
//   kinds: advance_cpp_double advance_c_double advance_cpp_float advance_c_float
//          batch_c_double (a batch of 1000 states a call; steps counts states)
//          model_cpp_double model_c_double model_cpp_float model_c_float
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gyro/gyro.h"
#include "model_workload.hpp"

namespace {

inline void barrier() { asm volatile("" ::: "memory"); }

template <typename T>
gyro::RotorParameters<T> report_rotor() {
  return gyro::ReportSample<T>::rotor();
}

__attribute__((noinline)) int advance_cpp_double(long n) {
  gyro::RotorTransition<double> tr;
  if (gyro::make_transition(report_rotor<double>(), 1e-3, tr) != gyro::Status::kOk) return 1;
  const gyro::Vector2<double> torque(40.0, -25.0);
  gyro::RotorState<double> s;
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::advance(tr, torque, s));
  }
  return bad | (s.angle_rad(0) == 42.0);
}

__attribute__((noinline)) int advance_cpp_float(long n) {
  gyro::RotorTransition<float> tr;
  if (gyro::make_transition(report_rotor<float>(), 1e-3f, tr) != gyro::Status::kOk) return 1;
  const gyro::Vector2<float> torque(40.0f, -25.0f);
  gyro::RotorState<float> s;
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::advance(tr, torque, s));
  }
  return bad | (s.angle_rad(0) == 42.0f);
}

__attribute__((noinline)) int advance_c_double(long n) {
  const gyro::RotorParameters<double> r = report_rotor<double>();
  const gyro_rotor_parameters_d p{r.pitch_inertia, r.yaw_inertia, r.friction, r.angular_momentum};
  gyro_transition_d tr;
  if (gyro_make_transition_d(&p, 1e-3, &tr) != GYRO_OK) return 1;
  const double torque[2] = {40.0, -25.0};
  double s[4] = {0, 0, 0, 0};
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= gyro_advance_d(&tr, torque, s);
  }
  return bad | (s[0] == 42.0);
}

__attribute__((noinline)) int advance_c_float(long n) {
  const gyro::RotorParameters<float> r = report_rotor<float>();
  const gyro_rotor_parameters_f p{r.pitch_inertia, r.yaw_inertia, r.friction, r.angular_momentum};
  gyro_transition_f tr;
  if (gyro_make_transition_f(&p, 1e-3f, &tr) != GYRO_OK) return 1;
  const float torque[2] = {40.0f, -25.0f};
  float s[4] = {0, 0, 0, 0};
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= gyro_advance_f(&tr, torque, s);
  }
  return bad | (s[0] == 42.0f);
}

__attribute__((noinline)) int batch_c_double(long n) {
  const gyro::RotorParameters<double> r = report_rotor<double>();
  const gyro_rotor_parameters_d p{r.pitch_inertia, r.yaw_inertia, r.friction, r.angular_momentum};
  gyro_transition_d tr;
  if (gyro_make_transition_d(&p, 1e-3, &tr) != GYRO_OK) return 1;
  const double torque[2] = {40.0, -25.0};
  constexpr long kBatch = 1000;
  std::vector<double> states(4 * kBatch, 0.0);
  int bad = 0;
  for (long i = 0; i < n; i += kBatch) {
    barrier();
    bad |= gyro_advance_batch_d(&tr, states.data(), kBatch, torque, 0, nullptr);
  }
  return bad | (states[0] == 42.0);
}

// GyroModel: the workload of model_workload.hpp (the report's gyro at 1 kHz, the body level,
// the torque reversed every 1000 steps), in C++ and through the C API with the same inputs.
template <typename T>
__attribute__((noinline)) int model_cpp(long n) {
  gyro::bench::ModelWorkload<T> w;
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= static_cast<int>(w.step());
  }
  return bad | (w.output() == T(42));
}

template <typename T>
struct CModel;
template <>
struct CModel<double> {
  gyro_model_d_storage storage;
  gyro_model_d* m = gyro_model_d_init(&storage, sizeof storage);
  gyro_step_input_d in{};
  int configure(const gyro_model_config* c) { return gyro_model_d_configure(m, c, nullptr); }
  int uncage(const double* r, const double* w) { return gyro_model_d_uncage(m, r, w, nullptr); }
  int step(const double* t) { return gyro_model_d_step_torque(m, &in, t); }
  double output() const {
    double g[2];
    gyro_model_d_gimbal(m, g);
    return g[0];
  }
};
template <>
struct CModel<float> {
  gyro_model_f_storage storage;
  gyro_model_f* m = gyro_model_f_init(&storage, sizeof storage);
  gyro_step_input_f in{};
  int configure(const gyro_model_config* c) { return gyro_model_f_configure(m, c, nullptr); }
  int uncage(const float* r, const float* w) { return gyro_model_f_uncage(m, r, w, nullptr); }
  int step(const float* t) { return gyro_model_f_step_torque(m, &in, t); }
  float output() const {
    float g[2];
    gyro_model_f_gimbal(m, g);
    return g[0];
  }
};

template <typename T>
__attribute__((noinline)) int model_c(long n) {
  gyro_report_sample sample;
  gyro_model_config config;
  if (gyro_report_sample_get(&sample, &config) != GYRO_OK) return 1;
  CModel<T> c;
  const T identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[2] = {0, 0};
  if (c.configure(&config) != GYRO_OK || c.uncage(identity, zero) != GYRO_OK) return 1;
  c.in.dt_s = T(1e-3);
  c.in.spin_hz = static_cast<T>(sample.spin_hz);
  for (int i = 0; i < 9; ++i) c.in.R_earth_to_body[i] = identity[i];
  const gyro::bench::Case k = gyro::bench::find_case("report");
  const T torque[2][2] = {{static_cast<T>(k.torque(0)), static_cast<T>(k.torque(1))},
                          {-static_cast<T>(k.torque(0)), -static_cast<T>(k.torque(1))}};
  int bad = 0;
  for (long i = 0; i < n; ++i) {
    barrier();
    bad |= c.step(torque[(i / 1000) & 1]);
  }
  return bad | (c.output() == T(42));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <kind> <steps>\n", argv[0]);
    return 2;
  }
  const std::string kind = argv[1];
  const long n = std::strtol(argv[2], nullptr, 10);
  int bad = -1;
  if (kind == "advance_cpp_double") bad = advance_cpp_double(n);
  if (kind == "advance_c_double") bad = advance_c_double(n);
  if (kind == "advance_cpp_float") bad = advance_cpp_float(n);
  if (kind == "advance_c_float") bad = advance_c_float(n);
  if (kind == "batch_c_double") bad = batch_c_double(n);
  if (kind == "model_cpp_double") bad = model_cpp<double>(n);
  if (kind == "model_c_double") bad = model_c<double>(n);
  if (kind == "model_cpp_float") bad = model_cpp<float>(n);
  if (kind == "model_c_float") bad = model_c<float>(n);
  if (bad != 0) std::fprintf(stderr, "%s: %s\n", kind.c_str(), bad < 0 ? "unknown kind" : "a step refused");
  return bad == 0 ? 0 : 1;
}
