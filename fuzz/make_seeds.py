#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (fuzz/corpus/<target>/).

The binary targets read their input with gyro::fuzz::Bytes (fuzz_support.hpp); the encoders
below produce exactly that format. The scenario parser's seeds are the shipped scenarios and
a few of the refused ones from tests/data/bad_scenarios.

    fuzz/make_seeds.py          # rewrites the corpus directories (deterministic)
"""
import math
import pathlib
import shutil
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"

# --- Bytes::value encodings --------------------------------------------------------------
# Specials (index into the table of Bytes::special).
NAN, NEG_NAN, INF, NEG_INF, DENORM, NEG_DENORM, TINY, NEG_TINY, HUGE, NEG_HUGE = range(10)


def zero():
    return b"\x00"


def special(i):
    return bytes([1, i])


def f64(v):
    return b"\x07" + struct.pack("<d", v)


def f32(v):
    return b"\x07" + struct.pack("<f", v)


def small(i8):  # scale * 1e-3 * i8/127
    return bytes([6]) + struct.pack("<b", i8)


def linear(fraction):  # scale * i16/32767
    return bytes([2]) + struct.pack("<h", int(round(fraction * 32767)))


# --- fuzz_rotor_step ----------------------------------------------------------------------
def rotor(j1, j2, f, h, dt, state=(0.0, 0.0, 0.0, 0.0), torques=((0.0, 0.0),), float_bytes=False, enc=f64):
    head = ((len(torques) - 1) << 1) | (1 if float_bytes else 0)
    out = bytes([head])
    vals = [j1, j2, f, h, dt, *state]
    for t in torques:
        vals += list(t)
    for v in vals:
        out += v if isinstance(v, bytes) else enc(v)
    if float_bytes:  # the float case, decoded from its own bytes
        for v in vals:
            out += v if isinstance(v, bytes) else f32(v)
    return out


def rotor_seeds():
    h_report = 2 * math.pi * 100.0 * 3.0
    h_seeker = 2 * math.pi * 400.0 * 3e-5
    return {
        "report_rotor": rotor(2.25, 2.0, 5.0, h_report, 1e-3, (0, 0, 0.01, -0.02), ((1.0, -2.0), (0.5, 0.5))),
        "seeker_si": rotor(2e-5, 2e-5, 4e-4, h_seeker, 5e-4, (1e-3, -1e-3, 0.1, 0.2), ((1e-3, 2e-3),)),
        "critical_damping": rotor(1.0, 0.25, 2.0, 1.5, 0.1, (0, 0, 1, 1), ((1, 0), (0, 1), (-1, 0))),
        "overdamped_stiff": rotor(1.0, 0.01, 10.0, 0.1, 1.0, (0, 0, 1, -1), ((0.3, 0.1),)),
        "free_no_spin_no_friction": rotor(1.0, 1.0, 0.0, 0.0, 0.5, (0, 0, 1, 2), ((1, 1), (1, 1))),
        "fast_nutation_long_step": rotor(1e-3, 2e-3, 1e-6, 1e6, 10.0, (0, 0, 1e-3, 0), ((1, 1),)),
        "nan_parameters": rotor(special(NAN), 1.0, 1.0, 1.0, 1e-3),
        "infinite_step": rotor(1.0, 1.0, 1.0, 1.0, special(INF), (0, 0, 1, 1)),
        "denormal_inertia": rotor(special(DENORM), 1.0, 1.0, 1e3, 1e-3, (0, 0, 1, 1), ((1, 1),)),
        "negative_friction": rotor(1.0, 1.0, -1.0, 1.0, 1e-3),
        "float_bytes": rotor(2.25, 2.0, 5.0, h_report, 1e-3, (0, 0, 0.01, 0), ((1, 0), (0, 1)), float_bytes=True),
        "huge_torques_eight_steps": rotor(1.0, 2.0, 0.5, 3.0, 0.2, (0, 0, 0, 0),
                                          tuple((special(HUGE), special(NEG_HUGE)) for _ in range(8))),
        "huge_state": rotor(1.0, 1.0, 1.0, 1.0, 1.0, (special(HUGE), 0, special(HUGE), 0), ((0, 0),)),
    }


# --- fuzz_component_tick -------------------------------------------------------------------
ANGLES, SEQUENCE, VALID, READ_FAIL, WRITE_FAIL, REQUEST, SLEW, NAV, TICK, POKE, REPEAT = (1 << i for i in range(11))
NONE, CAGE, UNCAGE = 0, 1, 2


def op(bits, *payload):
    return struct.pack("<H", bits) + b"".join(payload)


def repeat(n):  # n more ticks with the same operation
    return bytes([n])


def u8(v):
    return bytes([v])


def component(*ops, float_=False, overrides=None, before_activate=False, no_friction_comp=False, no_readback=False):
    head = (1 if float_ else 0) | (2 if overrides is not None else 0) | (4 if before_activate else 0)
    head |= (8 if no_friction_comp else 0) | (16 if no_readback else 0)
    out = bytes([head])
    if overrides is not None:
        out += overrides
    return out + b"".join(ops)


def uncage_and_settle():
    return [op(REPEAT, repeat(20)), op(REQUEST, u8(UNCAGE)), op(REPEAT, repeat(10))]


def component_seeds():
    def v(x, float_=False):
        return f32(x) if float_ else f64(x)

    slew = lambda p, y, fl=False: op(SLEW | REPEAT, v(p, fl), v(y, fl), repeat(30))
    return {
        "caged_steady": component(op(REPEAT, repeat(200))),
        "caged_steady_float": component(op(REPEAT, repeat(200)), float_=True),
        "uncage_free_slew_cage": component(*uncage_and_settle(), slew(0.2, -0.1), op(REQUEST, u8(CAGE)),
                                           op(REPEAT, repeat(20))),
        "uncage_free_slew_float": component(*uncage_and_settle(), slew(0.5, 0.5, True), op(REQUEST, u8(CAGE)),
                                            float_=True),
        "pickoff_walk": component(*[op(ANGLES, small(i), small(-i)) for i in range(0, 120, 4)],
                                  op(REQUEST, u8(UNCAGE)), *[op(ANGLES, small(i), small(i)) for i in range(30)]),
        "read_failures_fault_then_cage": component(op(READ_FAIL | REPEAT, u8(2), repeat(8)), op(REQUEST, u8(CAGE)),
                                                   op(REPEAT, repeat(10)), op(REQUEST, u8(CAGE))),
        "write_failures": component(op(WRITE_FAIL | REPEAT, u8(3), repeat(5)), op(REPEAT, repeat(5))),
        "refused_commands": component(op(REPEAT, repeat(5)), op(SLEW, special(NAN), zero()), op(SLEW, zero(), zero()),
                                      op(REQUEST, u8(3)), op(REQUEST, u8(253)), op(NAV, u8(8), special(INF), zero()),
                                      op(NAV, u8(8), zero(), zero()), op(REPEAT, repeat(3))),
        "ticks_repeat_gap_back": component(op(REPEAT, repeat(5)), op(TICK, u8(0)), op(TICK, u8(7)), op(TICK, u8(205)),
                                           op(TICK, u8(255), struct.pack("<Q", 2**64 - 1)), op(0), op(0)),
        "navigation_bad": component(op(NAV, u8(1)), op(REPEAT, repeat(3)), op(NAV, u8(1 | 2), small(10), small(20),
                                    small(-5)), op(NAV, u8(4), u8(4), linear(0.5)), op(NAV, u8(4), u8(0x80), zero()),
                                    op(REQUEST, u8(UNCAGE)), op(NAV, u8(2), special(NAN), zero(), zero())),
        "spin_low_readback": component(op(VALID | REPEAT, u8(1 | 2 | 4), f64(100.0), repeat(10)),
                                       op(VALID, u8(1 | 2 | 4), special(HUGE)), op(REPEAT, repeat(5))),
        "stale_invalid_sequence": component(op(SEQUENCE, u8(0)), op(SEQUENCE, u8(1)), op(SEQUENCE, u8(2), b"\xff" * 4),
                                            op(VALID, u8(0)), op(VALID, u8(1)), op(ANGLES, special(NAN), zero()),
                                            op(ANGLES, zero(), zero()), op(REPEAT, repeat(8))),
        "config_overrides": component(op(REPEAT, repeat(20)), op(REQUEST, u8(UNCAGE)), slew(1.0, 1.0),
                                      overrides=struct.pack("<I", (1 << 9) | (1 << 7) | (1 << 22)) +
                                      f64(1e300) + f64(1e300) + u8(0)),
        "idle_then_poke": component(op(POKE), op(REPEAT | POKE, repeat(4)), before_activate=True,
                                    no_friction_comp=True, no_readback=True),
    }


# --- fuzz_frame_decoder --------------------------------------------------------------------
# An encoder of docs/pil-protocol.md written from the document: sync 0xA5 0x5A, type (bit 7:
# binary64 reals), sequence, length, payload, CRC-16/CCITT-FALSE (little-endian) over type ..
# payload.
def crc16(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) if crc & 0x8000 else (crc << 1)
            crc &= 0xFFFF
    return crc


def frame(msg_id, payload, double, seq=0):
    body = bytes([msg_id | (0x80 if double else 0), seq & 0xFF, len(payload)]) + payload
    return b"\xa5\x5a" + body + struct.pack("<H", crc16(body))


def reals(values, double):
    return struct.pack("<%d%s" % (len(values), "d" if double else "f"), *values)


def pickoff(seq, pitch, yaw, double, status=3, conversion=None):
    conv = seq if conversion is None else conversion
    return frame(0x01, struct.pack("<IB", conv, status) + reals([pitch, yaw, 400.0], double), double, seq)


def torque(seq, t1, t2, double):
    return frame(0x02, reals([t1, t2], double), double, seq)


def harness_frames(double):
    config = reals([1e-3, 2e-5, 2e-5, 3e-5, 4e-4, 400, 200, 1, 1, 0.04, 20, 0.35, 0.03, 0.01, 0.5, 5e-3,
                    0.02, 1.7e-3, 100, 0, 0], double) + bytes([3]) + struct.pack("<8I", 20, 10, 50, 50, 50, 8, 50, 25000)
    tick_in = struct.pack("<IBB", 7, 24, 0x6) + reals([0.3, -0.2, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.05, -0.03], double)
    tick_out = struct.pack("<IBIBIB4IB", 8, 1, 7, 0, 141, 15, 8, 8, 0, 0, 0) + struct.pack("<14I", *range(14))
    telemetry = struct.pack("<IBI", 7, 3, 4) + struct.pack("<21I", *range(21)) + reals(
        [0.01 * i for i in range(14)] + [1, 0, 0, 0, 400], double)
    return (frame(0x10, struct.pack("<HBI", 2, 8 if double else 4, 25000000), double, 0) +
            frame(0x11, config, double, 1) + frame(0x12, bytes(25), double, 2) + frame(0x13, tick_in, double, 3) +
            frame(0x14, tick_out, double, 4) + frame(0x15, telemetry, double, 5) + frame(0x16, b"\x00", double, 6))


def frame_decoder_seeds():
    seeds = {}
    for double in (False, True):
        kind = "double" if double else "float"
        head_link = 1 if double else 0
        clean = b"".join(pickoff(i, 0.001 * i, -0.002 * i, double) for i in range(4)) + torque(9, 0.01, -0.02, double)
        seeds[f"link_{kind}_clean"] = bytes([head_link]) + clean
        good = pickoff(5, 0.1, 0.2, double)
        bad_crc = bytearray(good)
        bad_crc[6] ^= 0x01
        seeds[f"link_{kind}_faults"] = bytes([head_link | (7 << 2)]) + (
            b"\x00\xa5\x13\x5a" + good[:10] + good + bytes(bad_crc) + good + good +
            pickoff(7, 0.1, 0.2, double, status=0x80) + torque(1, float("nan"), 0.0, double) + pickoff(9, 0.3, 0.1, double))
        seeds[f"harness_{kind}"] = bytes([2 | head_link]) + harness_frames(double)
    return seeds


# --- fuzz_scenario_parser ------------------------------------------------------------------
BAD_SEEDS = ["bad_json.json", "bad_fault_kind.json", "missing_field.json", "unknown_key.json",
             "schedule_out_of_order.json", "wrong_type_integer.json", "duplicate_key.json",
             "integer_wraps.json", "control_characters_in_key.json", "deep_nesting.json",
             "overflow_spin.json", "overflow_torquer_scale.json", "overflow_float_slew.json",
             "overflow_component_rotor.json"]


def main():
    targets = {
        "fuzz_rotor_step": rotor_seeds(),
        "fuzz_component_tick": component_seeds(),
        "fuzz_frame_decoder": frame_decoder_seeds(),
    }
    for target, seeds in targets.items():
        d = CORPUS / target
        shutil.rmtree(d, ignore_errors=True)
        d.mkdir(parents=True)
        for name, data in seeds.items():
            (d / f"seed_{name}").write_bytes(data)
    d = CORPUS / "fuzz_scenario_parser"
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    for p in sorted((ROOT / "scenarios").glob("*.json")):
        shutil.copyfile(p, d / f"seed_{p.name}")
    for name in BAD_SEEDS:
        shutil.copyfile(ROOT / "tests" / "data" / "bad_scenarios" / name, d / f"seed_{name}")
    for target in [*targets, "fuzz_scenario_parser"]:
        print(target, len(list((CORPUS / target).iterdir())), "seeds")


if __name__ == "__main__":
    main()
