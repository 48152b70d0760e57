#!/usr/bin/env python3
"""An independent derivation of the two-axis gimbal's equations of motion, checked against the
C++ right-hand side (hil_stub/include/gyro/gimbal_dynamics.hpp).

Built from scratch here, sharing nothing with the C++ but the definitions of the device
(docs/gimbal-plant.md): the three rotation matrices C_BO = Rz(psi), C_BI = C_BO Ry(theta),
C_BR = C_BI Rx(phi); each body's angular velocity from its matrix, w_F = C^T w_B +
vee(C^T dC/dt); the kinetic energy of the three bodies; Lagrange's equations
d/dt dT/dq' - dT/dq = Q with the body's rate (p, q, r) a prescribed function of time; the
generalised forces from the virtual work of each torque on the body it acts on and its
reaction (the joint rates read off the matrices, not assumed), and from the unbalance's
potential m d (f . x_I). The C++ equations are Kane's, written in the gimbal frames.

    gimbal_lagrange_check.py DUMP_EXECUTABLE [CASES]

runs tests/gimbal_rhs_dump.cpp's executable, evaluates both at its random states, and fails
if any quantity differs by more than 1e-10 relative to its scale.
"""
import subprocess
import sys
import time

import numpy as np
import sympy as sp

TOLERANCE = 1e-10


def rot_x(a):
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def vee(m):
    return sp.Matrix([m[2, 1], m[0, 2], m[1, 0]])


def derive():
    # Plain symbols throughout; time derivatives by the chain rule through q, q' and w_B.
    th, ps, ph = sp.symbols("theta psi phi")
    thd, psd, phd = sp.symbols("theta_d psi_d phi_d")
    pb, qb, rb, pbd, qbd, rbd = sp.symbols("p q r p_d q_d r_d")
    coords, speeds = [th, ps, ph], [thd, psd, phd]
    w_body = sp.Matrix([pb, qb, rb])

    def time_derivative(e):  # with q'' = 0: what Lagrange's equations leave besides M q''
        return sum(sp.diff(e, c) * sd for c, sd in zip(coords, speeds)) + \
            sum(sp.diff(e, w) * wd for w, wd in zip((pb, qb, rb), (pbd, qbd, rbd)))

    rates = [pb, qb, rb] + speeds

    def tidy(e):  # an angular velocity component is linear in the rates: simplify each coefficient
        e = sp.expand(e)
        linear = sum(e.coeff(x) * x for x in rates)
        assert sp.expand(e - linear) == 0
        return sum(sp.trigsimp(e.coeff(x)) * x for x in rates)

    def frame_rate(c_bf):  # angular velocity of frame F in F axes, C_BF(q) relative to the body
        c_dot = c_bf.applyfunc(time_derivative)
        return (c_bf.T * w_body + vee(c_bf.T * c_dot)).applyfunc(tidy)

    c_bo = rot_z(ps)
    c_bi = c_bo * rot_y(th)
    c_br = c_bi * rot_x(ph)
    w_o, w_i, w_r = frame_rate(c_bo), frame_rate(c_bi), frame_rate(c_br)

    j0, a, ix, iy, iz, ox, oy, oz = sp.symbols("J0 A Ix Iy Iz Ox Oy Oz", positive=True)
    j_o, j_i, j_r = sp.diag(ox, oy, oz), sp.diag(ix, iy, iz), sp.diag(j0, a, a)
    energy = ((w_o.T * j_o * w_o)[0] + (w_i.T * j_i * w_i)[0] + (w_r.T * j_r * w_r)[0]) / 2

    # Lagrange: d/dt dT/dq'_j - dT/dq_j = M_jk q''_k + rest_j.
    momenta = [sp.diff(energy, sd) for sd in speeds]
    mass = [[sp.diff(pj, sd) for sd in speeds] for pj in momenta]
    rest = [time_derivative(pj) - sp.diff(energy, c) for pj, c in zip(momenta, coords)]

    # Generalised forces: a torque tau (in a body's own axes) on that body contributes
    # tau . dw_body/dq'_j; on the prescribed body it contributes nothing.
    def q_of(tau, w):
        return [(tau.T * w.diff(sd))[0] for sd in speeds]

    def add(*qs):
        return [sum(v) for v in zip(*qs)]

    def neg(qv):
        return [-v for v in qv]

    chi, md, fx, fy, fz = sp.symbols("chi md fx fy fz")
    e1, e2, e3 = sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])
    one = sp.Integer(1)

    # Unit torques, each between the two bodies it acts on (the body's side does no work):
    # about the pitch joint (y) between outer and inner gimbal; about the yaw joint (body z)
    # between body and outer gimbal; about the spin axis between inner gimbal and rotor; about
    # the gyro's non-rolling axes (the inner gimbal's y, z turned by chi about x) between body
    # and inner gimbal. Torquers, friction, motor and drag are these times their magnitudes.
    y_g, z_g = rot_x(chi) * e2, rot_x(chi) * e3
    q_pitch_unit = add(q_of(one * e2, w_i), neg(q_of(one * e2, w_o)))
    q_yaw_unit = q_of(one * e3, w_o)
    q_spin_unit = add(q_of(one * e1, w_r), neg(q_of(one * e1, w_i)))
    q_gyro_y_unit, q_gyro_z_unit = q_of(y_g, w_i), q_of(z_g, w_i)
    # The rates the friction laws act on, read off the frames: the relative angular velocity
    # about each joint axis, and the inner gimbal's inertial rates about the gyro axes.
    joint_rates = [(rot_y(th) * w_i - w_o)[1], (c_bo * w_o - w_body)[2], (rot_x(ph) * w_r - w_i)[0]]
    gyro_rates = [(w_i.T * y_g)[0], (w_i.T * z_g)[0]]
    # Unbalance: potential m d (f . x_I), f the specific force in body axes.
    potential = md * (sp.Matrix([fx, fy, fz]).T * (c_bi * e1))[0]
    q_unbalance = [-sp.diff(potential, c) for c in coords]
    twist_rate = -w_i[0]

    args = [j0, a, ix, iy, iz, ox, oy, oz, md, th, ps, ph, thd, psd, phd, chi,
            pb, qb, rb, pbd, qbd, rbd, fx, fy, fz]
    exprs = {
        "mass": mass, "rest": rest,
        "q_pitch_unit": q_pitch_unit, "q_yaw_unit": q_yaw_unit, "q_spin_unit": q_spin_unit,
        "q_gyro_y_unit": q_gyro_y_unit, "q_gyro_z_unit": q_gyro_z_unit, "q_unbalance": q_unbalance,
        "joint_rates": joint_rates, "gyro_rates": gyro_rates, "twist_rate": twist_rate,
        "energy": energy, "momenta": momenta, "dT_dphi": sp.diff(energy, ph),
    }
    return {k: sp.lambdify(args, v, modules="numpy", cse=True) for k, v in exprs.items()}


def evaluate(fn, row):
    """The independent model at one case of the dump: dict of the compared quantities."""
    args = [row[k] for k in ("J0", "A", "Ix", "Iy", "Iz", "Ox", "Oy", "Oz", "unbalance")]
    args += [row["theta"], row["psi"], 0.7, row["theta_d"], row["psi_d"], row["phi_d"], row["chi"],
             row["p"], row["q"], row["r"], row["p_d"], row["q_d"], row["r_d"], row["fx"], row["fy"], row["fz"]]

    def vec(name):
        return np.array(fn[name](*args), dtype=float)

    def friction(rate, f, c):
        return -f * rate - c * np.tanh(rate / row["c_scale"])

    m, rest = np.array(fn["mass"](*args), dtype=float), vec("rest")
    pitch_rel, yaw_rel, spin_rel = vec("joint_rates")
    if row["axes"] == 1.0:  # the gyro's axes
        w1, w2 = vec("gyro_rates")
        unit_1, unit_2 = vec("q_gyro_y_unit"), vec("q_gyro_z_unit")
        fr_1, fr_2 = friction(w1, row["f_in"], row["c_in"]), friction(w2, row["f_out"], row["c_out"])
    else:
        unit_1, unit_2 = vec("q_pitch_unit"), vec("q_yaw_unit")
        fr_1 = friction(pitch_rel, row["f_in"], row["c_in"])
        fr_2 = friction(yaw_rel, row["f_out"], row["c_out"])
    q_torquer = unit_1 * row["T1"] + unit_2 * row["T2"]
    q_friction = unit_1 * fr_1 + unit_2 * fr_2
    q_motor = vec("q_spin_unit")
    q_drag = q_motor * (-row["drag"] * spin_rel)
    q_unbalance = vec("q_unbalance")
    b = q_torquer + q_friction + q_drag + q_unbalance - rest
    speeds = np.array([row["theta_d"], row["psi_d"], row["phi_d"]])

    motor_torque, saturated = 0.0, 0.0
    if row["drive"] == 1.0:  # phi'' = bandwidth (command - phi'); unknowns theta'', psi'', Tm
        phi_dd = row["bandwidth"] * (row["spin_cmd"] - row["phi_d"])
        lhs = np.column_stack([m[:, 0], m[:, 1], -q_motor])
        x = np.linalg.solve(lhs, b - m[:, 2] * phi_dd)
        acc, motor_torque = np.array([x[0], x[1], phi_dd]), x[2]
        if abs(motor_torque) > row["limit"]:
            motor_torque, saturated = np.copysign(row["limit"], motor_torque), 1.0
            acc = np.linalg.solve(m, b + q_motor * motor_torque)
    else:
        acc = np.linalg.solve(m, b)
    momenta = vec("momenta")
    return {
        "theta_dd": acc[0], "psi_dd": acc[1], "phi_dd": acc[2],
        "chi_d": float(fn["twist_rate"](*args)), "motor_torque": motor_torque, "saturated": saturated,
        "P_torquer": q_torquer @ speeds, "P_friction": q_friction @ speeds,
        "P_spin": (q_motor * motor_torque + q_drag) @ speeds, "P_unbalance": q_unbalance @ speeds,
        "energy": float(fn["energy"](*args)),
        "p_theta": momenta[0], "p_psi": momenta[1], "p_phi": momenta[2],
        "dT_dphi": float(fn["dT_dphi"](*args)),
    }


# Each compared quantity and the scale its difference is measured against.
GROUPS = {
    "accelerations": ["theta_dd", "psi_dd", "phi_dd"],
    "twist rate": ["chi_d"],
    "motor torque": ["motor_torque"],
    "powers": ["P_torquer", "P_friction", "P_spin", "P_unbalance"],
    "kinetic energy": ["energy"],
    "generalised momenta": ["p_theta", "p_psi", "p_phi"],
}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    cases = sys.argv[2] if len(sys.argv) > 2 else "300"
    start = time.time()
    dump = subprocess.run([sys.argv[1], cases], check=True, capture_output=True, text=True).stdout.split("\n")
    names = dump[0].split()
    rows = [dict(zip(names, map(float, line.split()))) for line in dump[1:] if line.strip()]
    fn = derive()
    derived = time.time()

    worst = {g: (0.0, None) for g in GROUPS}
    saturated_cases = mismatched_saturation = 0
    worst_dt_dphi = 0.0
    for k, row in enumerate(rows):
        ref = evaluate(fn, row)
        saturated_cases += int(ref["saturated"])
        mismatched_saturation += int(ref["saturated"] != row["saturated"])
        worst_dt_dphi = max(worst_dt_dphi, abs(ref["dT_dphi"]) / ref["energy"])
        for g, keys in GROUPS.items():
            scale = max(max(abs(ref[x]) for x in keys), max(abs(row[x]) for x in keys))
            for x in keys:
                err = abs(row[x] - ref[x]) / scale if scale > 0 else abs(row[x] - ref[x])
                if err > worst[g][0]:
                    worst[g] = (err, f"case {k} {x}: C++ {row[x]:.17g} Lagrange {ref[x]:.17g}")

    # Canary: the comparison sees a missing term (the reference without the outer gimbal's
    # moment about the yaw axis, a small part of the yaw joint's inertia).
    canary = 0.0
    for row in rows:
        if row["Oz"] > 0.0:
            ref = evaluate(fn, dict(row, Oz=0.0))
            scale = max(abs(ref[x]) for x in GROUPS["accelerations"])
            canary = max(canary, max(abs(row[x] - ref[x]) / scale for x in GROUPS["accelerations"]))

    print(f"{len(rows)} random states ({saturated_cases} with the spin motor at its limit); "
          f"derivation {derived - start:.1f} s, evaluation {time.time() - derived:.1f} s")
    print(f"  dT/dphi (axisymmetric rotor: 0) worst {worst_dt_dphi:.1e} of T")
    print(f"  canary: without the outer gimbal's Oz the accelerations differ by up to {canary:.1e}")
    failed = mismatched_saturation > 0 or worst_dt_dphi > TOLERANCE or canary < 1e3 * TOLERANCE
    for g, (err, where) in worst.items():
        print(f"  {g:20s} worst relative difference {err:.2e}" + (f"  ({where})" if err > TOLERANCE else ""))
        failed = failed or err > TOLERANCE
    if mismatched_saturation:
        print(f"  motor saturation differs in {mismatched_saturation} cases")
    print("FAIL" if failed else f"PASS (tolerance {TOLERANCE:g})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
