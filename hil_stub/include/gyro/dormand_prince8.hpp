// One step of the eighth-order Runge-Kutta method of Dormand and Prince (the 12-stage
// eighth-order solution of DOP853; Hairer, Norsett & Wanner, Solving ODEs I, 2nd ed., II.10;
// coefficients as in Hairer's dop853.f, to double precision), with DOP853's local error
// estimate when asked. No step control here: the gimbal plant chooses its sub-steps per tick
// (docs/gimbal-plant.md).
//
// Per step, on the imaginary axis (an undamped oscillation of phase k = omega h per step):
// amplitude error 4.5e-11 and phase error 2.5e-10 per radian at k = 0.5, 9.4e-10 and 3.7e-9 at
// k = 0.7, 2.4e-8 and 6.3e-8 at k = 1 (from the method's stability polynomial).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>

namespace gyro {

struct DormandPrince8 {
  static constexpr int kStages = 12;
  static constexpr std::array<double, kStages> c = {
      0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274, 0.2816496580927726,
      0.3333333333333333, 0.25, 0.3076923076923077, 0.6512820512820513, 0.6, 0.8571428571428571, 1.0};
  static constexpr std::array<double, kStages> b = {
      0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003,
      -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034,
      0.04471061572777259};
  // a(i, j), j < i, row by row: row i starts at i (i - 1) / 2.
  static constexpr std::array<double, kStages*(kStages - 1) / 2> a = {
      0.05260015195876773,
      0.0197250569845379, 0.0591751709536137,
      0.02958758547680685, 0.0, 0.08876275643042054,
      0.2413651341592667, 0.0, -0.8845494793282861, 0.924834003261792,
      0.037037037037037035, 0.0, 0.0, 0.17082860872947386, 0.12546768756682242,
      0.037109375, 0.0, 0.0, 0.17025221101954405, 0.06021653898045596, -0.017578125,
      0.03709200011850479, 0.0, 0.0, 0.17038392571223998, 0.10726203044637328,
      -0.015319437748624402, 0.008273789163814023,
      0.6241109587160757, 0.0, 0.0, -3.3608926294469414, -0.868219346841726, 27.59209969944671,
      20.154067550477894, -43.48988418106996,
      0.47766253643826434, 0.0, 0.0, -2.4881146199716677, -0.590290826836843, 21.230051448181193,
      15.279233632882423, -33.28821096898486, -0.020331201708508627,
      -0.9371424300859873, 0.0, 0.0, 5.186372428844064, 1.0914373489967295, -8.149787010746927,
      -18.52006565999696, 22.739487099350505, 2.4936055526796523, -3.0467644718982196,
      2.273310147516538, 0.0, 0.0, -10.53449546673725, -2.0008720582248625, -17.9589318631188,
      27.94888452941996, -2.8589982771350235, -8.87285693353063, 12.360567175794303,
      0.6433927460157636};
};

// The error estimate of DOP853: the fifth-order (er) and third-order (b - bhh) embedded
// solutions' differences from the eighth, combined as h err5^2 / sqrt(err5^2 + err3^2 / 100),
// which behaves as the eighth-order solution's error does (Hairer's dop853.f, with its sums of
// squares). bhh weighs stages 1, 9, 12; er stages 1 and 6 to 12.
struct DormandPrince8Error {
  static constexpr std::array<double, 3> bhh = {0.244094488188976377952755905512, 0.733846688281611857341361741547,
                                                0.0220588235294117647058823529412};
  static constexpr std::array<double, 8> er = {
      0.1312004499419488073250102996e-01,  -0.1225156446376204440720569753e+01, -0.4957589496572501915214079952,
      0.1664377182454986536961530415e+01,  -0.3503288487499736816886487290,     0.3341791187130174790297318841,
      0.8192320648511571246570742613e-01,  -0.2235530786388629525884427845e-01};
};

// Advances x over [t, t + h] of x' = f(t, x). `rhs(t, x, dx, q)` writes x' into dx and, when
// q is not null, into *q quantities whose time integral is wanted (powers, a torque): they do
// not feed back, so the method's weights give their integral over the step, added to
// *integral (null: none wanted). With `error_weight`, returns the step's error estimate in
// the norm sqrt(sum (weight_i e_i)^2); else 0.
namespace dp8_detail {
// x + h sum_j a(i, j) k_j over the nonzero a(i, j), written out at compile time.
template <std::size_t I, typename Vec, typename T, std::size_t... J>
void stage_state(Vec& xi, const Vec& x, T h, const std::array<Vec, DormandPrince8::kStages>& k,
                 std::index_sequence<J...> /*j < i*/) noexcept {
  constexpr std::size_t kRow = I * (I - 1) / 2;
  Vec sum = Vec::Zero();
  ((DormandPrince8::a[kRow + J] != 0.0 ? (void)(sum += static_cast<T>(DormandPrince8::a[kRow + J]) * k[J]) : (void)0),
   ...);
  xi = x + h * sum;
}

template <typename T, int N, int M, typename Rhs, std::size_t... I>
void stages(Rhs& rhs, T t, T h, const Eigen::Matrix<T, N, 1>& x,
            std::array<Eigen::Matrix<T, N, 1>, DormandPrince8::kStages>& k, Eigen::Matrix<T, M, 1>* q,
            Eigen::Matrix<T, M, 1>& q_sum, std::index_sequence<I...> /*stages*/) noexcept {
  Eigen::Matrix<T, N, 1> xi;
  auto stage = [&](auto i_tag) noexcept {
    constexpr std::size_t kI = decltype(i_tag)::value;
    if constexpr (kI == 0) {
      xi = x;
    } else {
      stage_state<kI>(xi, x, h, k, std::make_index_sequence<kI>{});
    }
    rhs(t + static_cast<T>(DormandPrince8::c[kI]) * h, xi, k[kI], q);
    if constexpr (DormandPrince8::b[kI] != 0.0) {
      if (q != nullptr) q_sum += static_cast<T>(DormandPrince8::b[kI]) * *q;
    }
  };
  (stage(std::integral_constant<std::size_t, I>{}), ...);
}
}  // namespace dp8_detail

// Advances x over [t, t + h] of x' = f(t, x). `rhs(t, x, dx, q)` writes x' into dx and, when
// q is not null, into *q quantities whose time integral is wanted (powers, a torque): they do
// not feed back, so the method's weights give their integral over the step, added to
// *integral (null: none wanted). With `error_weight`, returns the step's error estimate in
// the norm sqrt(sum (weight_i e_i)^2); else 0.
template <typename T, int N, int M, typename Rhs>
T dormand_prince8_step(Rhs& rhs, T t, T h, Eigen::Matrix<T, N, 1>& x, Eigen::Matrix<T, M, 1>* integral,
                       const Eigen::Matrix<T, N, 1>* error_weight = nullptr) noexcept {
  using Tab = DormandPrince8;
  using Vec = Eigen::Matrix<T, N, 1>;
  std::array<Vec, Tab::kStages> k;
  Eigen::Matrix<T, M, 1> q_stage;
  Eigen::Matrix<T, M, 1> q_sum = Eigen::Matrix<T, M, 1>::Zero();
  dp8_detail::stages(rhs, t, h, x, k, integral != nullptr ? &q_stage : nullptr, q_sum,
                     std::make_index_sequence<Tab::kStages>{});
  // b is zero for stages 2 to 5.
  const Vec dx_sum = static_cast<T>(Tab::b[0]) * k[0] + static_cast<T>(Tab::b[5]) * k[5] +
                     static_cast<T>(Tab::b[6]) * k[6] + static_cast<T>(Tab::b[7]) * k[7] +
                     static_cast<T>(Tab::b[8]) * k[8] + static_cast<T>(Tab::b[9]) * k[9] +
                     static_cast<T>(Tab::b[10]) * k[10] + static_cast<T>(Tab::b[11]) * k[11];
  x += h * dx_sum;
  if (integral != nullptr) *integral += h * q_sum;
  if (error_weight == nullptr) return T(0);
  using E = DormandPrince8Error;
  const Vec e3 = dx_sum - static_cast<T>(E::bhh[0]) * k[0] - static_cast<T>(E::bhh[1]) * k[8] -
                 static_cast<T>(E::bhh[2]) * k[11];
  Vec e5 = static_cast<T>(E::er[0]) * k[0];
  for (std::size_t i = 5; i < k.size(); ++i) e5 += static_cast<T>(E::er[i - 4]) * k[i];
  const T err5 = e5.cwiseProduct(*error_weight).squaredNorm();
  const T err3 = e3.cwiseProduct(*error_weight).squaredNorm();
  const T deno = err5 + err3 / T(100);
  return deno > T(0) ? std::abs(h) * err5 / std::sqrt(deno) : T(0);
}

}  // namespace gyro
