// The report's driver GYMAIN, run against the drop-in GYRO with a tap (gyro_tap.f), leaves a
// trace of every call: the COMMON blocks going in and coming out. This runs GyroModel in C++ on
// the same inputs, as the drop-in's rules say (fortran/report/gyro.f: GYRO(0) takes ROTEG, the
// next step uncages from it turned by THETA, PSI with the rates THETAD, PSID; ROTEB as its
// nearest rotation), in the program's REAL kind, and compares every output of every call.
//
//   gymain_replay TRACE float|double STEPS TOLERANCE
// Prints the largest differences; fails if any exceeds TOLERANCE (rad, rad/s), if a flag is
// raised, or if the run did not take STEPS steps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gyro/gyro.h"
#include "gyro/gyro_model.hpp"

namespace {

using gyro::Matrix3;
using gyro::Vector2;

struct Record {
  std::vector<double> in, out;
};

std::vector<Record> read_trace(const char* path) {
  std::ifstream f(path);
  std::vector<Record> r;
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    std::vector<double> v;
    for (double x = 0; s >> x;) v.push_back(x);
    if (tag == "IN") r.push_back({v, {}});
    if (tag == "OUT" && !r.empty()) r.back().out = v;
  }
  return r;
}

// Fortran's R(i, j), column by column as the trace has it.
template <typename T>
Matrix3<T> matrix(const std::vector<double>& v, std::size_t at) {
  Matrix3<T> m;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) m(i, j) = static_cast<T>(v[at + static_cast<std::size_t>(3 * j + i)]);
  }
  return m;
}

int nearest(const Matrix3<double>& r, Matrix3<double>& out) {
  double a[9], b[9];
  for (int k = 0; k < 9; ++k) a[k] = r(k / 3, k % 3);
  const int st = gyro_nearest_rotation_d(a, b);
  for (int k = 0; k < 9; ++k) out(k / 3, k % 3) = b[k];
  return st;
}
int nearest(const Matrix3<float>& r, Matrix3<float>& out) {
  float a[9], b[9];
  for (int k = 0; k < 9; ++k) a[k] = r(k / 3, k % 3);
  const int st = gyro_nearest_rotation_f(a, b);
  for (int k = 0; k < 9; ++k) out(k / 3, k % 3) = b[k];
  return st;
}

// The configuration from COMMON/GYROD/ (the drop-in's mapping; docs/seed-errata.md, 14:
// GERROR(:,1) drifts yaw, GERROR(:,2) pitch).
template <typename T>
gyro::GyroModelConfig<T> config_of(const std::vector<double>& in) {
  const std::size_t c = 28;  // GJ1 GJ2 F GIMBAL THTDMX PSIDMX GERROR(12) GJ0 G
  gyro::GyroModelConfig<T> g;
  g.pitch_inertia = static_cast<T>(in[c]);
  g.yaw_inertia = static_cast<T>(in[c + 1]);
  g.friction = static_cast<T>(in[c + 2]);
  g.gimbal_cone_limit_rad = static_cast<T>(in[c + 3]);
  g.max_pitch_rate_rad_s = static_cast<T>(in[c + 4]);
  g.max_yaw_rate_rad_s = static_cast<T>(in[c + 5]);
  gyro::AxisErrorSources<T>* axes[2] = {&g.errors.yaw, &g.errors.pitch};
  for (std::size_t j = 0; j < 2; ++j) {
    const auto e = [&](std::size_t k) { return static_cast<T>(in[c + 6 + 6 * j + k]); };
    *axes[j] = {e(0), e(1), e(2), e(3), e(4), e(5)};
  }
  g.spin_inertia = static_cast<T>(in[c + 18]);
  g.gravity = static_cast<T>(in[c + 19]);
  return g;
}

struct Worst {
  double gimbal = 0, rate = 0, isaf = 0, roteg = 0;
};

template <typename T>
int replay(const std::vector<Record>& trace, int steps_expected, double tolerance) {
  gyro::GyroModel<T> g;
  Matrix3<T> rotc = Matrix3<T>::Identity();
  bool uncage_pending = false;
  std::vector<double> configured;  // COMMON/GYROD/'s configuration, as last configured
  int steps = 0;
  Worst w;
  for (const Record& r : trace) {
    if (r.in.size() != 48 || r.out.size() != 18) {
      std::fprintf(stderr, "a trace record of %zu and %zu numbers\n", r.in.size(), r.out.size());
      return 1;
    }
    const T tdelta = static_cast<T>(r.in[0]);
    if (!(tdelta > T(0))) {  // GYRO(0.): uncaging
      rotc = matrix<T>(r.in, 10);
      uncage_pending = true;
      continue;
    }
    const std::vector<double> config(r.in.begin() + 28, r.in.end());
    if (config != configured) {
      if (!g.configure(config_of<T>(r.in)).ok()) return 1;
      configured = config;
    }
    if (uncage_pending) {
      Matrix3<T> start;
      if (nearest(rotc, start) != GYRO_OK) return 1;
      const Vector2<T> rates(static_cast<T>(r.in[6]), static_cast<T>(r.in[7]));
      const Vector2<T> offset(static_cast<T>(r.in[8]), static_cast<T>(r.in[9]));
      if (g.uncage(start, rates, offset) != gyro::Status::kOk) return 1;
      uncage_pending = false;
    }
    gyro::GyroStepInput<T> in;
    in.dt_s = tdelta;
    if (nearest(matrix<T>(r.in, 19), in.R_earth_to_body) != GYRO_OK) return 1;
    in.body_accel = Vector2<T>(static_cast<T>(r.in[4]), static_cast<T>(r.in[5]));
    in.spin_hz = static_cast<T>(r.in[3]);
    const Vector2<T> slew(static_cast<T>(r.in[1]), static_cast<T>(r.in[2]));
    if (g.step_slew(in, slew) != gyro::Status::kOk) return 1;
    ++steps;
    const auto diff = [](double a, T b) { return std::abs(a - static_cast<double>(b)); };
    const std::vector<double>& o = r.out;
    w.rate = std::max({w.rate, diff(o[0], g.rate_rad_s()(0)), diff(o[1], g.rate_rad_s()(1))});
    w.isaf = std::max({w.isaf, diff(o[2], g.isaf_angle_rad()(0)), diff(o[3], g.isaf_angle_rad()(1))});
    const Matrix3<T> roteg = g.R_earth_to_gyro();
    for (int k = 0; k < 9; ++k) w.roteg = std::max(w.roteg, diff(o[4 + static_cast<std::size_t>(k)], roteg(k % 3, k / 3)));
    w.gimbal = std::max({w.gimbal, diff(o[13], g.gimbal_pitch_rad()), diff(o[14], g.gimbal_yaw_rad())});
    if (o[16] != 0.0 || o[17] != 0.0 || g.flags() != 0u) {
      std::fprintf(stderr, "step %d: a flag was raised (IGLE %g, ISAE %g, model %u)\n", steps, o[16], o[17], g.flags());
      return 1;
    }
  }
  std::printf("GYMAIN (%s) against GyroModel in C++ over %d steps: largest difference of the gimbal angles %.3g rad, "
              "of the rates %.3g rad/s, of the ISAF angles %.3g rad, of ROTEG %.3g\n",
              sizeof(T) == 8 ? "REAL*8, double" : "REAL*4, float", steps, w.gimbal, w.rate, w.isaf, w.roteg);
  if (steps != steps_expected) {
    std::fprintf(stderr, "%d steps, expected %d\n", steps, steps_expected);
    return 1;
  }
  return std::max({w.gimbal, w.rate, w.isaf, w.roteg}) <= tolerance ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s TRACE float|double STEPS TOLERANCE\n", argv[0]);
    return 2;
  }
  const std::vector<Record> trace = read_trace(argv[1]);
  const int steps = std::atoi(argv[3]);
  const double tolerance = std::atof(argv[4]);
  return std::string(argv[2]) == "float" ? replay<float>(trace, steps, tolerance) : replay<double>(trace, steps, tolerance);
}
