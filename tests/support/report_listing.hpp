// The report's GYMAIN/INITG/GYRO transliterated line by line (double precision), with
// switches that fix its errors one by one. A test reference only: it uses the report's own
// closed form (eqs 9-19, underdamped only), independent of the library's matrix exponential.
#pragma once

#include <cmath>

namespace gyro::report {

struct ListingFixes {
  bool reset_isaf_angles = false;     // THETA = PSI = 0 at each step (the text says so)
  bool keep_gimbal_angles = false;    // do not fall into label 10's GIMBY = GIMBZ = 0
  bool exact_rotations = false;       // exact ROT and body rotations instead of first order
  bool correct_renormalisation = false;  // REN = SQRT(REN/3.) instead of SQRT(REN)/3.
  bool body_before_gyro = false;      // move the body first: no one-step lag of the gimbals
  static ListingFixes all() { return {true, true, true, true, true}; }
};

struct Mat3 {
  double a[3][3];
};

inline Mat3 identity() {
  Mat3 m{};
  for (int i = 0; i < 3; ++i) m.a[i][i] = 1.0;
  return m;
}
inline Mat3 mul(const Mat3& x, const Mat3& y) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r.a[i][j] += x.a[i][k] * y.a[k][j];
  return r;
}

// Frame rotation for rotation vector (0, theta, psi) by Rodrigues: I - sin(n)/n K + (1-cos n)/n^2 K^2
// with K the cross-product matrix; its first order is the listing's ROT.
inline Mat3 rot_exact(double theta, double psi) {
  const double k[3][3] = {{0, -psi, theta}, {psi, 0, 0}, {-theta, 0, 0}};
  const double n2 = theta * theta + psi * psi, n = std::sqrt(n2);
  const double s = (n == 0) ? 1.0 : std::sin(n) / n;
  const double c = (n == 0) ? 0.5 : (1.0 - std::cos(n)) / n2;
  Mat3 r = identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double k2 = 0;
      for (int l = 0; l < 3; ++l) k2 += k[i][l] * k[l][j];
      r.a[i][j] += -s * k[i][j] + c * k2;
    }
  return r;
}

class Listing {
 public:
  // COMMON/GYROD/ and /SIXDOF/ of the sample run.
  double gj0 = 3.0, gj1 = 2.25, gj2 = 2.0, gimbal = 0.4363323, thtdmx = 0.1745329,
         psidmx = 0.1745329, gspin = 100.0, f = 5.0, pi = 3.1415927;
  double thetad = 0, psid = 0, theta = 0, psi = 0, thtdcm = 0, psidcm = 0, h = 0;
  double gimby = 0, gimbz = 0;
  int igle = 0, isae = 0;
  Mat3 roteg = identity(), roteb = identity(), rotc = identity();
  int nct = 0;  // never initialised in the listing; a static zero here
  ListingFixes fix{};

  double initg_nutation_hz() const {
    const double hh = 2. * pi * gspin * gj0;
    const double alpha = (f / 2.) * (1. / gj1 + 1. / gj2);
    const double beta = std::sqrt((f * f + hh * hh) / (gj1 * gj2) - alpha * alpha);
    return beta / (2. * pi);
  }
  double initg_step() const { return 1. / std::floor(initg_nutation_hz() * 20.); }

  void gyro(double tdelta) {
    igle = 0;
    isae = 0;
    if (tdelta <= 0.) {
      label10();
      return;
    }
    double tt1 = psidcm, tt2 = thtdcm;
    if (std::fabs(tt1) > thtdmx) tt1 = std::copysign(thtdmx, tt1);  // limits paired as printed
    if (std::fabs(tt2) > psidmx) tt2 = std::copysign(psidmx, tt2);  // (equal in the sample)
    h = 2. * pi * gspin * gj0;
    const double t1 = h * tt1, t2 = -h * tt2;
    const double alpha = (f / 2.) * (1. / gj1 + 1. / gj2);
    const double beta = std::sqrt((f * f + h * h) / (gj1 * gj2) - alpha * alpha);
    double x[14];
    x[1] = f * f + h * h;
    x[2] = beta * gj1;
    x[3] = alpha * gj1 - f;
    x[4] = alpha * alpha + beta * beta;
    x[5] = std::sin(beta * tdelta);
    x[6] = std::cos(beta * tdelta);
    x[7] = std::exp(-alpha * tdelta);
    x[8] = (f * t1 - h * t2) / x[1];
    x[9] = (h * t1 + f * t2) / x[1];
    const double gk2 = thetad - x[8], gk4 = psid - x[9];
    const double gk1 = (x[3] * gk2 - h * gk4) / x[2];
    const double gk3 = (x[3] * gk1 + x[2] * gk2) / h;
    x[10] = (gk1 * beta + gk2 * alpha) / x[4];
    x[11] = (gk1 * alpha - gk2 * beta) / x[4];
    x[12] = (gk3 * beta + gk4 * alpha) / x[4];
    x[13] = (gk3 * alpha - gk4 * beta) / x[4];
    if (fix.reset_isaf_angles) theta = psi = 0.;
    theta = theta + x[8] * tdelta + x[10] - x[7] * (x[11] * x[5] + x[10] * x[6]);
    psi = psi + x[9] * tdelta + x[12] - x[7] * (x[13] * x[5] + x[12] * x[6]);
    thetad = x[8] + x[7] * (gk1 * x[5] + gk2 * x[6]);
    psid = x[9] + x[7] * (gk3 * x[5] + gk4 * x[6]);
    const double amnuty = std::sqrt((gk1 * gk1 + gk2 * gk2) / x[4]);
    const double amnutz = std::sqrt((gk3 * gk3 + gk4 * gk4) / x[4]);
    nutation_theta = amnuty;
    nutation_psi = amnutz;
    if (amnuty > .01 || amnutz > .01) isae = 1;
    if (std::fabs(theta) > .01 || std::fabs(psi) > .01) isae = 1;
    Mat3 rot = identity();
    if (fix.exact_rotations) {
      rot = rot_exact(theta, psi);
    } else {
      rot.a[0][1] = psi;
      rot.a[0][2] = -theta;
      rot.a[1][0] = -psi;
      rot.a[2][0] = theta;
    }
    roteg = mul(rot, rotc);
    double gp[3] = {0, 0, 0};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) gp[j] += roteb.a[j][k] * roteg.a[0][k];
    const double temp = std::sqrt(gp[0] * gp[0] + gp[1] * gp[1]);
    gimby = std::atan2(gp[2], temp);
    gimbz = std::atan2(-gp[1], gp[0]);
    if (gp[0] > std::cos(gimbal)) {
      label10();
      return;
    }
    igle = 1;  // (the per-axis test compared an angle with a cosine; never reached here)
  }

  double nutation_theta = 0, nutation_psi = 0;

 private:
  void label10() {
    if (nct < 0 || nct > 20) nct = 0;
    if (!fix.keep_gimbal_angles) gimby = gimbz = 0.;
    nct = nct + 1;
    if (nct >= 20) {
      double ren = 0.;
      for (auto& row : roteg.a)
        for (double v : row) ren += v * v;
      ren = fix.correct_renormalisation ? std::sqrt(ren / 3.) : std::sqrt(ren) / 3.;
      for (auto& row : roteg.a)
        for (double& v : row) v /= ren;
    }
    rotc = roteg;
  }
};

// GYMAIN: returns the number of steps completed before a STOP (801 if none).
template <typename OnStep>
int run_gymain(Listing& g, OnStep on_step) {
  const double tstep = g.initg_step();
  const double el = .1745329 * tstep;
  Mat3 roty = identity(), rotz = identity();
  if (g.fix.exact_rotations) {
    const double cy = std::cos(2.3 * el), sy = std::sin(2.3 * el);
    const double cz = std::cos(1.8 * el), sz = std::sin(1.8 * el);
    roty.a[0][0] = roty.a[2][2] = cy;
    rotz.a[0][0] = rotz.a[1][1] = cz;
    roty.a[2][0] = sy;
    roty.a[0][2] = -sy;
    rotz.a[0][1] = sz;
    rotz.a[1][0] = -sz;
  } else {
    roty.a[2][0] = 2.3 * el;
    roty.a[0][2] = -2.3 * el;
    rotz.a[0][1] = 1.8 * el;
    rotz.a[1][0] = -1.8 * el;
  }
  g.gimby = g.gimbz = 0.;
  g.gyro(0.);
  g.thetad = 2.3 * el / tstep;
  g.psid = 1.8 * el / tstep;
  g.theta = g.psi = 0.;
  double t = 0.;
  for (int kk = 0; kk <= 800; ++kk) {
    g.thtdcm = -.19;
    g.psidcm = .013;
    if (g.fix.body_before_gyro) g.roteb = mul(mul(rotz, roty), g.roteb);
    g.gyro(tstep);
    if (g.igle == 1 || g.isae == 1) return kk;
    t += tstep;
    if (!g.fix.body_before_gyro) g.roteb = mul(mul(rotz, roty), g.roteb);
    on_step(kk, t);
  }
  return 801;
}

}  // namespace gyro::report
