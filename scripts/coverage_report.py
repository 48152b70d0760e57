#!/usr/bin/env python3
"""Structural coverage of the flight libraries (component/ and port/), with MC/DC, from a run of
the suite built with clang's source-based coverage (cmake/coverage-scope.list instruments those
two libraries only; presets host-asan and host-coverage).

Merges the run's profiles (LLVM_PROFILE_FILE), exports the coverage of every instrumented binary
of the build (llvm-cov export), and per file of component/ and port/ counts lines, regions
(statements), branches (each condition's two outcomes) and MC/DC conditions (each condition of a
decision of two or more shown to change the decision on its own). Template instantiations are
merged by source location: a branch outcome or a condition is covered when some instantiation
covers it.

The gate: every branch outcome and every MC/DC condition covered, or its condition listed in the
reviewed exceptions of docs/coverage.md (section "Exceptions", a table of file, decision,
condition and the reason no test from the interface can reach it). It fails on an uncovered
condition that is not listed, on a listed one that is covered now or no longer exists, and on a
row whose reason starts "open:" (a gap listed but not reviewed: it needs a test or the argument).

    scripts/coverage_report.py --build build/host-asan                 # report and gate
    scripts/coverage_report.py --build build/host-asan --write-doc     # and rewrite docs/coverage.md
"""

import argparse
import json
import mmap
import os
import pathlib
import re
import subprocess
import sys
from collections import defaultdict

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs/coverage.md"
SCOPE = ("component/", "port/")
LLVM = os.environ.get("GYRO_LLVM_SUFFIX", "-19")
BEGIN = "<!-- generated: coverage (scripts/coverage_report.py) -->"
END = "<!-- end generated: coverage -->"


def tool(name):
    return f"{name}{LLVM}"


# Objects that are compiled but never linked into a test: tests/flight_rules_check.cpp
# instantiates every template of the libraries, so its functions that no test calls count as
# uncovered instead of being absent from the report.
COMPILE_ONLY = ["tests/CMakeFiles/gyro_flight_rules_check.dir/flight_rules_check.cpp.o"]


def instrumented_binaries(build):
    """ELF executables of the build that carry a coverage map, then the compile-only objects."""
    found = []
    for path in sorted(build.rglob("*")):
        if not path.is_file() or not os.access(path, os.X_OK) or path.suffix in (".so", ".o", ".a", ".py", ".sh"):
            continue
        try:
            with open(path, "rb") as f:
                if f.read(4) != b"\x7fELF":
                    continue
                with mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
                    if m.find(b"__llvm_covmap") >= 0:
                        found.append(path)
        except (OSError, ValueError):
            continue
    for obj in COMPILE_ONLY:
        if not (build / obj).is_file():
            sys.exit(f"coverage: {build / obj} not built (target gyro_flight_rules_check)")
        found.append(build / obj)
    return found


def merge_profiles(build):
    raws = sorted((build / "profiles").glob("*.profraw"))
    if not raws:
        sys.exit(f"coverage: no profiles in {build / 'profiles'} (run the suite with LLVM_PROFILE_FILE set)")
    data = build / "coverage.profdata"
    subprocess.run([tool("llvm-profdata"), "merge", "-sparse", "-o", str(data)] + [str(r) for r in raws], check=True)
    return data


def export(build, data, binaries):
    cmd = [tool("llvm-cov"), "export", "-format=text", f"-instr-profile={data}", str(binaries[0])]
    for b in binaries[1:]:
        cmd += ["-object", str(b)]
    cmd += [str(ROOT / s) for s in SCOPE]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def relative(name):
    p = pathlib.Path(name).resolve()
    try:
        return str(p.relative_to(ROOT))
    except ValueError:
        return None


class Source:
    """A source file's lines, to quote a region."""

    def __init__(self, path):
        self.lines = (ROOT / path).read_text().splitlines()

    def text(self, ls, cs, le, ce):
        if ls == le:
            s = self.lines[ls - 1][cs - 1:ce - 1]
        else:
            s = self.lines[ls - 1][cs - 1:] + "\n" + "\n".join(self.lines[ls:le - 1]) + "\n" + self.lines[le - 1][:ce - 1]
        return " ".join(s.split())


def analyse(exported):
    """Per file: LLVM's line, region and function summary, and the merged branches and MC/DC."""
    files = {}
    for f in exported["data"][0]["files"]:
        name = relative(f["filename"])
        if name is None or not name.startswith(SCOPE):
            continue
        src = Source(name)
        # Branches: [ls, cs, le, ce, true, false, file_id, expanded_file_id, kind], one record per
        # instantiation; merged by location. Only the file's own regions (not macro expansions).
        branches = {}
        for b in f["branches"]:
            key = tuple(b[0:4])
            t, fl = branches.get(key, (False, False))
            branches[key] = (t or b[4] > 0, fl or b[5] > 0)
        # MC/DC: [ls, cs, le, ce, expanded_file_id, kind, [covered per condition]].
        decisions = {}
        for r in f.get("mcdc_records", []):
            key = tuple(r[0:4])
            covered = r[-1]
            prev = decisions.get(key)
            decisions[key] = covered if prev is None else [a or b for a, b in zip(prev, covered)]
        # The conditions of a decision: its branch regions in source order (nested decisions'
        # conditions excluded).
        decision_conditions = {}
        for key, covered in decisions.items():
            inside = [b for b in branches if within(b, key)]
            nested = [d for d in decisions if d != key and within(d, key)]
            own = sorted((b for b in inside if not any(within(b, d) for d in nested)), key=lambda b: (b[0], b[1]))
            decision_conditions[key] = own if len(own) == len(covered) else None
        files[name] = {
            "summary": f["summary"],
            "src": src,
            "branches": branches,
            "decisions": decisions,
            "conditions": decision_conditions,
        }
    return files


def within(inner, outer):
    return (inner[0], inner[1]) >= (outer[0], outer[1]) and (inner[2], inner[3]) <= (outer[2], outer[3])


def uncovered(files):
    """Every uncovered item: (file, line, decision text, condition text, what)."""
    items = []
    for name, f in files.items():
        src = f["src"]
        in_mcdc = set()
        for key, covered in f["decisions"].items():
            conds = f["conditions"][key]
            decision = src.text(*key)
            for i, ok in enumerate(covered):
                if conds is not None:
                    in_mcdc.add(conds[i])
                if ok:
                    continue
                cond = src.text(*conds[i]) if conds is not None else f"C{i + 1}"
                line = conds[i][0] if conds is not None else key[0]
                items.append((name, line, decision, cond, "MC/DC: not shown to change the decision on its own"))
        for key, (t, fl) in f["branches"].items():
            if key in in_mcdc or (t and fl):
                continue
            cond = src.text(*key)
            missing = "never true" if not t and fl else "never false" if t and not fl else "never evaluated"
            items.append((name, key[0], cond, cond, f"branch: {missing}"))
    return sorted(items, key=lambda i: (i[0], i[1], i[3]))


def read_exceptions(doc):
    """The reviewed exceptions: rows of the table under "## Exceptions" in docs/coverage.md."""
    if not doc.is_file():
        return []
    rows, in_section = [], False
    for n, line in enumerate(doc.read_text().splitlines(), 1):
        if line.startswith("## "):
            in_section = line.strip() == "## Exceptions"
            continue
        if not in_section or not line.startswith("| `"):
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip()[1:-1])]
        if len(cells) < 4:
            continue
        unquote = lambda c: c.strip("`").replace("\\|", "|")
        rows.append({"file": unquote(cells[0]), "decision": unquote(cells[1]), "condition": unquote(cells[2]),
                     "reason": cells[3], "line": n, "open": cells[3].startswith("open:")})
    return rows


def pct(covered, count):
    return "–" if count == 0 else f"{100.0 * covered / count:.1f} %"


def figures(files):
    rows, total = [], defaultdict(int)
    for name in sorted(files):
        f = files[name]
        s = f["summary"]
        br_count = 2 * len(f["branches"])
        br_cov = sum(int(t) + int(fl) for t, fl in f["branches"].values())
        mc_count = sum(len(c) for c in f["decisions"].values())
        mc_cov = sum(sum(1 for x in c if x) for c in f["decisions"].values())
        row = {
            "file": name,
            "lines": (s["lines"]["covered"], s["lines"]["count"]),
            "regions": (s["regions"]["covered"], s["regions"]["count"]),
            "branches": (br_cov, br_count),
            "mcdc": (mc_cov, mc_count),
            "decisions": len(f["decisions"]),
        }
        for k in ("lines", "regions", "branches", "mcdc"):
            total[k + "_c"] += row[k][0]
            total[k + "_n"] += row[k][1]
        total["decisions"] += row["decisions"]
        rows.append(row)
    return rows, total


def part_of(name):
    """The library a file belongs to, as the README names them."""
    for prefix in ("component/exact/", "component/report/", "component/flight/", "port/include/gyro/link/", "port/"):
        if name.startswith(prefix):
            return prefix.rstrip("/")
    return name


def render(files, items, exceptions, matched):
    rows, total = figures(files)
    out = [BEGIN, ""]
    out.append(
        f"{len(files)} files; {total['decisions']} decisions of two or more conditions, "
        f"{total['mcdc_n']} conditions in them; {total['branches_n'] // 2} conditions in all "
        f"({total['branches_n']} branch outcomes). Uncovered: {len(items)} "
        f"({sum(1 for i in items if i in matched and not matched[i]['open'])} of them reviewed exceptions, "
        f"{sum(1 for i in items if i in matched and matched[i]['open'])} open: listed, not yet reviewed).")
    out += ["", "| file | lines | statements (regions) | branches | MC/DC conditions |", "|---|--:|--:|--:|--:|"]
    parts = defaultdict(lambda: defaultdict(int))
    for r in rows:
        cells = [f"{pct(*r[k])} ({r[k][0]}/{r[k][1]})" for k in ("lines", "regions", "branches", "mcdc")]
        out.append(f"| `{r['file']}` | " + " | ".join(cells) + " |")
        p = parts[part_of(r["file"])]
        for k in ("lines", "regions", "branches", "mcdc"):
            p[k + "_c"] += r[k][0]
            p[k + "_n"] += r[k][1]
    out += ["", "Per part and in total:", "", "| part | lines | statements (regions) | branches | MC/DC conditions |",
            "|---|--:|--:|--:|--:|"]
    for name in sorted(parts):
        p = parts[name]
        cells = [f"{pct(p[k + '_c'], p[k + '_n'])} ({p[k + '_c']}/{p[k + '_n']})" for k in ("lines", "regions", "branches", "mcdc")]
        out.append(f"| `{name}/` | " + " | ".join(cells) + " |")
    cells = [f"{pct(total[k + '_c'], total[k + '_n'])} ({total[k + '_c']}/{total[k + '_n']})"
             for k in ("lines", "regions", "branches", "mcdc")]
    out.append("| **total** | " + " | ".join(f"**{c}**" for c in cells) + " |")
    out += ["", "Uncovered conditions, each with its exception (by the table's row):", ""]
    if not items:
        out.append("None.")
    else:
        out += ["| file:line | condition | in the decision | what | exception |", "|---|---|---|---|---|"]
        for i in items:
            ex = matched.get(i)
            where = (f"row {exceptions.index(ex) + 1}" + (" (open)" if ex["open"] else "")) if ex else "**none**"
            out.append(f"| `{i[0]}:{i[1]}` | `{esc(i[3])}` | `{esc(i[2])}` | {i[4]} | {where} |")
    out += ["", END]
    return "\n".join(out)


def esc(s):
    return s.replace("|", "\\|")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", required=True, help="the build directory of the instrumented suite")
    ap.add_argument("--write-doc", action="store_true", help="rewrite the generated part of docs/coverage.md")
    ap.add_argument("--output", help="write the generated part here (default: BUILD/coverage.md)")
    args = ap.parse_args()
    build = pathlib.Path(args.build).resolve()

    binaries = instrumented_binaries(build)
    if not binaries:
        sys.exit(f"coverage: no instrumented executable in {build}")
    data = merge_profiles(build)
    files = analyse(export(build, data, binaries))
    items = uncovered(files)
    exceptions = read_exceptions(DOC)

    matched, used, problems = {}, set(), []
    for i in items:
        for n, ex in enumerate(exceptions):
            if ex["file"] == i[0] and ex["decision"] == i[2] and ex["condition"] == i[3]:
                matched[i] = ex
                used.add(n)
                break
    for i in items:
        if i not in matched:
            problems.append(f"{i[0]}:{i[1]}: `{i[3]}` in `{i[2]}`: {i[4]}, and no reviewed exception")
    for n, ex in enumerate(exceptions):
        if ex["open"]:
            problems.append(f"docs/coverage.md:{ex['line']}: exception `{ex['condition']}` in {ex['file']} "
                            "is open, not reviewed: add the test that covers it or argue why none can")
        elif n not in used:
            problems.append(f"docs/coverage.md:{ex['line']}: exception `{ex['condition']}` in {ex['file']} "
                            "is covered now or no longer exists: remove it")

    text = render(files, items, exceptions, matched)
    out = pathlib.Path(args.output) if args.output else build / "coverage.md"
    out.write_text(text + "\n")
    if args.write_doc:
        doc = DOC.read_text()
        start, end = doc.index(BEGIN), doc.index(END) + len(END)
        DOC.write_text(doc[:start] + text + doc[end:])
    _, total = figures(files)
    print(f"coverage of component/ and port/ ({len(binaries)} binaries): lines {pct(total['lines_c'], total['lines_n'])}, "
          f"statements {pct(total['regions_c'], total['regions_n'])}, branches "
          f"{pct(total['branches_c'], total['branches_n'])}, MC/DC {pct(total['mcdc_c'], total['mcdc_n'])} "
          f"({total['mcdc_c']}/{total['mcdc_n']} conditions); {len(items)} uncovered, "
          f"{sum(1 for e in matched.values() if not e['open'])} of them reviewed exceptions, "
          f"{sum(1 for e in matched.values() if e['open'])} open; report {out}")
    for p in problems:
        print(f"coverage: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
