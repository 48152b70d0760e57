#!/usr/bin/env python3
"""Tables of the flight component's instructions per tick, from scripts/tick-cost.sh's results.

  tick_cost_report.py --join SCENARIO TYPE CALLGRIND_OUT SIL_CSV   one scenario's steps as CSV rows
  tick_cost_report.py --tables RESULTS                             the Markdown tables
make_report.py imports sections() to fill docs/performance.md.
"""
import csv
import glob
import os
import re
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SETTLE_TICKS = 600  # bench/component_tick_case.hpp: kTickCaseSettleTicks


def fmt(x):
    return f"{int(round(x)):,}"


def flag_names():
    """The component's flag names, in bit order, from component_types.hpp (flag_name)."""
    for path in sorted(glob.glob(os.path.join(ROOT, "component", "**", "component_types.hpp"), recursive=True)):
        try:
            text = open(path).read()
        except OSError:
            continue
        m = re.search(r"kNames\[kComponentFlagCount\]\s*=\s*\{(.*?)\};", text, re.S)
        if m:
            return re.findall(r'"([a-z_]+)"', m.group(1))
    return []


NAMES = flag_names()


def describe_flags(flags):
    if flags == 0:
        return "none"
    bits = [b for b in range(32) if flags >> b & 1]
    return ", ".join(NAMES[b] if b < len(NAMES) else f"bit {b}" for b in bits)


def join(scenario, typ, cg_out, sil_csv):
    """Pairs the n-th callgrind dump (after the n-th step) with the n-th CSV row (tick n-1)."""
    parts = [int(line.split()[1]) for line in open(cg_out) if line.startswith("totals:")]
    with open(sil_csv) as f:
        rows = list(csv.DictReader(f))
    if len(parts) < len(rows) or any(parts[len(rows):]):
        sys.exit(f"tick_cost_report.py: {scenario} {typ}: {len(parts)} dumps for {len(rows)} ticks")
    w = csv.writer(sys.stdout, lineterminator="\n")
    for ir, r in zip(parts, rows):
        w.writerow([scenario, typ, r["tick"], ir, r["mode"], r["flags"], r["request"],
                    r["active_faults"], r["step_status"]])


def read_target(path):
    """gyro_fw_tick_cost's output: {case: (header fields, [(tick, instructions, mode, flags)])}."""
    cases = {}
    cur = None
    for line in open(path):
        f = line.split()
        if not f:
            continue
        if f[0] == "case" and len(f) == 10:
            cur = f[1]
            cases[cur] = (dict(zip(f[2::2], f[3::2])), [])
        elif f[0] == "tick" and cur and len(f) == 5:
            cases[cur][1].append((int(f[1]), int(f[2]), f[3], int(f[4])))
        else:
            sys.exit(f"tick_cost_report.py: {path}: unexpected line: {line.strip()}")
    return cases


def component_tick_table(rdir):
    host = {}
    with open(os.path.join(rdir, "component_tick.csv")) as f:
        for r in csv.DictReader(f):
            host.setdefault((r["type"], r["case"]), {})[int(r["ticks"])] = int(r["instructions"])
    def per_tick(key):
        runs = host.get(key, {})
        if len(runs) < 2:
            return float("nan")
        (n1, i1), (n2, i2) = sorted(runs.items())[:2]
        return (i2 - i1) / (n2 - n1)
    targets = {}
    for preset in ("cortex-m7", "cortex-m4f"):
        p = os.path.join(rdir, f"target_{preset}.txt")
        targets[preset] = read_target(p) if os.path.exists(p) else {}
    def target_free(preset, case):
        ticks = targets[preset].get(case, ({}, []))[1]
        free = [ir for k, ir, _, _ in ticks if k > SETTLE_TICKS]
        if not free:
            return "n/a"
        lo, hi = min(free), max(free)
        return fmt(lo) if lo == hi else f"{fmt(statistics.mean(free))} ({fmt(lo)}–{fmt(hi)})"
    lines = ["| spin readback | x86-64 double | x86-64 float | Cortex-M7 double | Cortex-M4F float |",
             "|---|--:|--:|--:|--:|"]
    for case, label in (("steady", "steady (the estimator's transition cached)"),
                        ("spin_down", "changing every tick (rotor running down: the transition rebuilt every tick)")):
        lines.append(f"| {label} | {fmt(per_tick(('double', case)))} | {fmt(per_tick(('float', case)))} | "
                     f"{target_free('cortex-m7', case)} | {target_free('cortex-m4f', case)} |")
    return "\n".join(lines), targets


def target_table(targets):
    lines = ["| target | spin readback | free flight: min / median / max | every tick: min / median / max | largest tick |",
             "|---|---|--:|--:|---|"]
    for preset, label in (("cortex-m7", "Cortex-M7, double"), ("cortex-m4f", "Cortex-M4F, float")):
        for case, (head, ticks) in targets.get(preset, {}).items():
            if not ticks:
                continue
            free = [ir for k, ir, _, _ in ticks if k > SETTLE_TICKS]
            every = [ir for _, ir, _, _ in ticks]
            k, ir, mode, flags = max(ticks, key=lambda t: t[1])
            lines.append(
                f"| {label} | {case.replace('_', ' ')} | {fmt(min(free))} / {fmt(statistics.median(free))} / {fmt(max(free))} | "
                f"{fmt(min(every))} / {fmt(statistics.median(every))} / {fmt(max(every))} | "
                f"tick {k}: {fmt(ir)}, {mode}, flags {describe_flags(flags)} |")
    return "\n".join(lines)


def read_steps(rdir):
    with open(os.path.join(rdir, "worst_tick.csv")) as f:
        return [dict(r, tick=int(r["tick"]), instructions=int(r["instructions"]), flags=int(r["flags"]))
                for r in csv.DictReader(f)]


def worst_tick_tables(rdir):
    steps = read_steps(rdir)
    groups = {}
    for s in steps:
        groups.setdefault((s["scenario"], s["type"]), []).append(s)
    lines = ["| scenario | scalar | ticks | min | median | max | largest tick: tick, mode, flags | modes |",
             "|---|---|--:|--:|--:|--:|---|---|"]
    for (scenario, typ), ss in sorted(groups.items()):
        irs = [s["instructions"] for s in ss]
        top = max(ss, key=lambda s: s["instructions"])
        modes = []
        for s in ss:
            if s["mode"] not in modes:
                modes.append(s["mode"])
        lines.append(f"| {scenario} | {typ} | {len(ss)} | {fmt(min(irs))} | {fmt(statistics.median(irs))} | "
                     f"{fmt(max(irs))} | {top['tick']}, {top['mode']}, {describe_flags(top['flags'])} | "
                     f"{', '.join(modes)} |")
    per_scenario = "\n".join(lines)
    lines = ["| mode | scalar | ticks | min | median | max | largest tick: scenario, tick, flags |",
             "|---|---|--:|--:|--:|--:|---|"]
    by_mode = {}
    for s in steps:
        by_mode.setdefault((s["mode"], s["type"]), []).append(s)
    for (mode, typ), ss in sorted(by_mode.items()):
        irs = [s["instructions"] for s in ss]
        top = max(ss, key=lambda s: s["instructions"])
        lines.append(f"| {mode} | {typ} | {len(ss)} | {fmt(min(irs))} | {fmt(statistics.median(irs))} | "
                     f"{fmt(max(irs))} | {top['scenario']}, {top['tick']}, {describe_flags(top['flags'])} |")
    per_mode = "\n".join(lines)
    bound = {typ: max(s["instructions"] for s in steps if s["type"] == typ) for typ in ("double", "float")}
    return per_scenario, per_mode, bound


def sections(rdir):
    """Placeholders of bench/performance.md.in."""
    table, targets = component_tick_table(rdir)
    per_scenario, per_mode, bound = worst_tick_tables(rdir)
    return {
        "COMPONENT_TICK": table,
        "TARGET_TICK": target_table(targets),
        "WORST_TICK_SCENARIOS": per_scenario,
        "WORST_TICK_MODES": per_mode,
        "WORST_TICK_DOUBLE": fmt(bound["double"]),
        "WORST_TICK_FLOAT": fmt(bound["float"]),
    }


def main(argv):
    if len(argv) == 6 and argv[1] == "--join":
        join(*argv[2:])
    elif len(argv) == 3 and argv[1] == "--tables":
        for k, v in sections(argv[2]).items():
            print(f"{k}:\n{v}\n")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
