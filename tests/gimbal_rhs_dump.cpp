// Prints the gimbal plant's right-hand side (gyro/gimbal_dynamics.hpp) and its kinetic energy
// and generalised momenta at random states, for tests/gimbal_lagrange_check.py to compare with
// Lagrange's equations derived symbolically. One header line of names, then one line per
// case; every number printed with 17 significant digits.
//
//   gimbal_rhs_dump [CASES]    (default 300; seeded, so the cases are the same every run)
#include <cstdio>
#include <cstdlib>
#include <random>

#include "gyro/gimbal_dynamics.hpp"

namespace {

using gyro::Vector2;
using gyro::Vector3;

struct Case {
  gyro::GimbalParameters<double> prm;
  gyro::GimbalJointState<double> s;
  gyro::GimbalDrive<double> drive;
  gyro::BodyInstant<double> body;
  double coulomb_scale = 0.0;
};

// Principal moments of a rigid body (triangle inequality) of size about `scale`.
Vector3<double> moments(std::mt19937_64& rng, double scale, bool may_be_zero) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  if (may_be_zero && std::uniform_int_distribution<int>(0, 3)(rng) == 0) return Vector3<double>::Zero();
  const double a = u(rng) * scale, b = u(rng) * scale;
  return Vector3<double>(a, b, std::abs(a - b) + (a + b - std::abs(a - b)) * u(rng));
}

Case random_case(std::mt19937_64& rng, int k) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double scale = (k % 2 == 0) ? 1e-5 : 1.0;  // SI seeker-sized or report-sized (slug ft^2)
  Case c;
  // A configuration folded by make_gimbal_parameters, as the plant does.
  gyro::GimbalPlantConfig<double> g;
  const double j0 = scale * (2.0 + u(rng));
  const double a = j0 * (0.55 + 0.4 * (u(rng) + 1.0) / 2.0);
  g.spin_inertia = j0;
  g.rotor_transverse_inertia = a;
  g.inner_gimbal_inertia = moments(rng, 0.3 * scale, true);
  g.outer_gimbal_inertia = moments(rng, 0.3 * scale, true);
  const Vector2<double> friction = Vector2<double>(0.5 + u(rng), 0.5 + u(rng)) * 20.0 * scale;
  g.inner_friction = friction(0);
  g.outer_friction = friction(1);
  const Vector2<double> coulomb = Vector2<double>(1.0 + u(rng), 1.0 + u(rng)) * 5.0 * scale;
  g.inner_coulomb_torque = coulomb(0);
  g.outer_coulomb_torque = coulomb(1);
  c.coulomb_scale = 0.01 * (1.5 + u(rng));
  g.coulomb_rate_scale_rad_s = c.coulomb_scale;
  const int drive = (k / 2) % 3;  // free, motor, motor with a limit it exceeds
  g.spin_drive = drive == 0 ? gyro::SpinDrive::kFree : gyro::SpinDrive::kMotor;
  g.spin_servo_bandwidth_rad_s = 20.0 * (1.0 + u(rng));
  g.spin_down_time_s = 1.0 / (1.0 + u(rng));  // drag J0 / time
  g.mass_unbalance = 10.0 * scale * u(rng);
  g.torquer_axes = ((k / 6) % 2 == 0) ? gyro::TorquerAxes::kGimbal : gyro::TorquerAxes::kGyro;
  c.prm = gyro::make_gimbal_parameters(g);
  c.s.pitch_rad = 1.2 * u(rng);
  c.s.yaw_rad = 1.2 * u(rng);
  c.s.pitch_rate_rad_s = 8.0 * u(rng);
  c.s.yaw_rate_rad_s = 8.0 * u(rng);
  c.s.spin_rate_rad_s = 2000.0 * (1.0 + 0.5 * u(rng));
  c.s.twist_rad = 3.0 * u(rng);
  c.drive.torque = Vector2<double>(u(rng), u(rng)) * 1e3 * scale;
  c.drive.spin_command_rad_s = c.s.spin_rate_rad_s + 50.0 * u(rng);
  c.body.rate_rad_s = Vector3<double>(u(rng), u(rng), u(rng)) * 6.0;
  c.body.rate_dot_rad_s2 = Vector3<double>(u(rng), u(rng), u(rng)) * 60.0;
  c.body.specific_force = Vector3<double>(u(rng), u(rng), u(rng)) * 100.0;
  // A limit well above what holding the spin takes, or well below it.
  c.prm.motor_torque_limit = drive == 1 ? 1e6 * scale : 1e-3 * scale;
  return c;
}

void print(double v, bool last = false) { std::printf("%.17g%s", v, last ? "\n" : " "); }

}  // namespace

int main(int argc, char** argv) {
  const int cases = argc > 1 ? std::atoi(argv[1]) : 300;
  std::printf(
      "J0 A Ix Iy Iz Ox Oy Oz f_in f_out c_in c_out c_scale drive limit bandwidth drag unbalance axes "
      "theta psi theta_d psi_d phi_d chi T1 T2 spin_cmd p q r p_d q_d r_d fx fy fz "
      "theta_dd psi_dd phi_dd chi_d motor_torque saturated P_torquer P_friction P_spin P_unbalance "
      "energy p_theta p_psi p_phi\n");
  std::mt19937_64 rng(20240917);
  for (int k = 0; k < cases; ++k) {
    const Case c = random_case(rng, k);
    const gyro::GimbalAccelerations<double> acc = gyro::gimbal_accelerations(c.prm, c.s, c.drive, c.body);
    const gyro::GimbalFrames<double> f = gyro::gimbal_frames(c.s.pitch_rad, c.s.yaw_rad);
    const gyro::GimbalBodyRates<double> w = gyro::gimbal_body_rates(f, c.s, c.body.rate_rad_s);
    const Vector3<double> p = gyro::gimbal_generalised_momentum(c.prm.inertia, f, w);
    const double in[] = {c.prm.inertia.rotor(0), c.prm.inertia.rotor(1), c.prm.inertia.inner(0),
                         c.prm.inertia.inner(1), c.prm.inertia.inner(2), c.prm.inertia.outer(0),
                         c.prm.inertia.outer(1), c.prm.inertia.outer(2), c.prm.friction(0), c.prm.friction(1),
                         c.prm.coulomb(0), c.prm.coulomb(1), c.coulomb_scale,
                         c.prm.spin_drive == gyro::SpinDrive::kMotor ? 1.0 : 0.0, c.prm.motor_torque_limit,
                         c.prm.servo_bandwidth, c.prm.spin_drag, c.prm.mass_unbalance,
                         c.prm.torquer_axes == gyro::TorquerAxes::kGyro ? 1.0 : 0.0, c.s.pitch_rad, c.s.yaw_rad,
                         c.s.pitch_rate_rad_s, c.s.yaw_rate_rad_s, c.s.spin_rate_rad_s, c.s.twist_rad,
                         c.drive.torque(0), c.drive.torque(1), c.drive.spin_command_rad_s, c.body.rate_rad_s(0),
                         c.body.rate_rad_s(1), c.body.rate_rad_s(2), c.body.rate_dot_rad_s2(0),
                         c.body.rate_dot_rad_s2(1), c.body.rate_dot_rad_s2(2), c.body.specific_force(0),
                         c.body.specific_force(1), c.body.specific_force(2)};
    for (const double v : in) print(v);
    const double out[] = {acc.pitch_acc, acc.yaw_acc, acc.spin_acc, acc.twist_rate, acc.motor_torque,
                          acc.motor_saturated ? 1.0 : 0.0, acc.torquer_power, acc.friction_power,
                          acc.spin_power, acc.unbalance_power, gyro::gimbal_kinetic_energy(c.prm.inertia, w),
                          p(0), p(1)};
    for (const double v : out) print(v);
    print(p(2), true);
  }
  return 0;
}
