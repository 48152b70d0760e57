// Wall time per simulated second of every contender, with Google Benchmark.
//
//   gyro_bench_wall --calibration=CALIBRATION_CSV [--benchmark_* flags]
//
// Benchmarks are named second/CASE/CONTENDER. Euler and AB2 run only their first
// kWallRunSteps steps (at the step size that meets the accuracy target); the counter
// `scale` is the factor that turns that time into the time per simulated second.
// tick/KIND benchmarks time one exact step at the report's gyro.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_problem.hpp"

namespace gyro::bench {
namespace {

constexpr long kWallRunSteps = 1L << 20;

struct CalibrationRow {
  std::string case_id, contender;
  long steps{};
  double tol{};
};

std::vector<CalibrationRow> read_calibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail("cannot read the calibration file");
  std::vector<CalibrationRow> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string field;
    std::vector<std::string> f;
    while (std::getline(ss, field, ',')) f.push_back(field);
    if (f.size() < 4) continue;
    rows.push_back({f[0], f[1], std::atol(f[2].c_str()), std::atof(f[3].c_str())});
  }
  return rows;
}

void register_second(const CalibrationRow& row) {
  const Case c = find_case(row.case_id);
  const LinearRhs r = make_rhs(c);
  const std::string name = "second/" + row.case_id + "/" + row.contender;
  const long steps = row.steps;
  const std::string& who = row.contender;
  benchmark::internal::Benchmark* b = nullptr;
  if (who.rfind("exact_propagate", 0) == 0) {
    b = benchmark::RegisterBenchmark(name.c_str(), [c, steps](benchmark::State& st) {
      for (auto _ : st) {
        RotorState<double> s;
        const bool ok = exact_propagate(c, steps, s, NoObserver{});
        benchmark::DoNotOptimize(ok);
        benchmark::DoNotOptimize(s);
      }
      st.counters["scale"] = 1.0;
    });
  } else if (who.rfind("exact_precomputed", 0) == 0) {
    b = benchmark::RegisterBenchmark(name.c_str(), [c, steps](benchmark::State& st) {
      for (auto _ : st) {
        RotorState<double> s;
        const bool ok = exact_precomputed(c, steps, s, NoObserver{});
        benchmark::DoNotOptimize(ok);
        benchmark::DoNotOptimize(s);
      }
      st.counters["scale"] = 1.0;
    });
  } else if (who == "dopri5") {
    const double tol = row.tol;
    b = benchmark::RegisterBenchmark(name.c_str(), [r, tol](benchmark::State& st) {
      for (auto _ : st) {
        OdeState x{};
        const std::size_t n = dopri5(r, tol, x, nullptr, NoObserver{});
        benchmark::DoNotOptimize(n);
        benchmark::DoNotOptimize(x);
      }
      st.counters["scale"] = 1.0;
    });
  } else if (who == "rk4" || who == "euler" || who == "ab2") {
    const long run = (who == "rk4") ? steps : std::min(steps, kWallRunSteps);
    const int method = (who == "rk4") ? 0 : (who == "euler") ? 1 : 2;
    b = benchmark::RegisterBenchmark(name.c_str(), [r, steps, run, method](benchmark::State& st) {
      for (auto _ : st) {
        Vec4 x = (method == 0)   ? rk4(r, steps, run, NoObserver{})
                 : (method == 1) ? euler(r, steps, run, NoObserver{})
                                 : ab2(r, steps, run, NoObserver{});
        benchmark::DoNotOptimize(x);
      }
      st.counters["scale"] = static_cast<double>(steps) / static_cast<double>(run);
    });
  }
  if (b != nullptr) b->Unit(benchmark::kMicrosecond);
}

void tick_advance_double(benchmark::State& st) {
  const Case c = find_case("report");
  RotorTransition<double> tr;
  if (make_transition(c.prm, 1e-3, tr) != Status::kOk) fail("make_transition");
  RotorState<double> s;
  for (auto _ : st) {
    benchmark::DoNotOptimize(advance(tr, c.torque, s));
    benchmark::ClobberMemory();
  }
}

void tick_advance_float(benchmark::State& st) {
  const Case c = find_case("report");
  const RotorParameters<float> p{static_cast<float>(c.prm.pitch_inertia),
                                 static_cast<float>(c.prm.yaw_inertia),
                                 static_cast<float>(c.prm.friction),
                                 static_cast<float>(c.prm.angular_momentum)};
  const Vector2<float> torque(static_cast<float>(c.torque(0)), static_cast<float>(c.torque(1)));
  RotorTransition<float> tr;
  if (make_transition(p, 1e-3f, tr) != Status::kOk) fail("make_transition");
  RotorState<float> s;
  for (auto _ : st) {
    benchmark::DoNotOptimize(advance(tr, torque, s));
    benchmark::ClobberMemory();
  }
}

void tick_propagate_double(benchmark::State& st) {
  const Case c = find_case("report");
  const double dt = (st.range(0) == 100) ? 0.01 : 0.001;
  RotorState<double> s;
  for (auto _ : st) {
    benchmark::DoNotOptimize(propagate(c.prm, dt, c.torque, s));
    benchmark::ClobberMemory();
  }
}

}  // namespace
}  // namespace gyro::bench

int main(int argc, char** argv) {
  std::string calibration;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strncmp(argv[i], "--calibration=", 14) == 0) {
      calibration = argv[i] + 14;
    } else {
      args.push_back(argv[i]);
    }
  }
  if (!calibration.empty()) {
    for (const auto& row : gyro::bench::read_calibration(calibration)) {
      gyro::bench::register_second(row);
    }
  }
  benchmark::RegisterBenchmark("tick/advance_double", gyro::bench::tick_advance_double);
  benchmark::RegisterBenchmark("tick/advance_float", gyro::bench::tick_advance_float);
  benchmark::RegisterBenchmark("tick/propagate_double_1khz", gyro::bench::tick_propagate_double)
      ->Arg(1000);
  benchmark::RegisterBenchmark("tick/propagate_double_100hz", gyro::bench::tick_propagate_double)
      ->Arg(100);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
