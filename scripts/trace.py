#!/usr/bin/env python3
"""Traceability of the requirements (docs/requirements.md) to the tests that verify them.

Reads the requirements and a test run's JUnit file (ctest --output-junit; the host test preset
writes build/host/junit.xml), and writes docs/traceability.md: requirement -> tests -> result of
the run, and test -> requirements. A GoogleTest names what it verifies with GYRO_VERIFIES
(tests/support/requirements.hpp) and reports its source file (tests/support/trace_main.cpp);
a ctest that is not a GoogleTest is named by the requirement itself ("ctest NAME").

Fails (exit 1), listing why, when
  - a requirement is malformed (no "shall", no rationale, no verification method), or an
    identifier is used twice;
  - a requirement verified by test has no passing test;
  - an analysis or inspection names no evidence, or names a file that does not exist;
  - a test names a requirement that does not exist, or a requirement names a ctest that did
    not run;
  - a test of the flight code (FLIGHT_TESTS below) traces to no requirement;
  - with --compare, the traceability it generates differs from the committed one.

    scripts/trace.py                       # build/host/junit.xml -> docs/traceability.md
    scripts/trace.py --junit build/host/junit.xml --output build/host/traceability.md \\
        --compare docs/traceability.md     # what scripts/test.sh runs
"""

import argparse
import fnmatch
import pathlib
import re
import sys
import xml.etree.ElementTree as ET
from collections import defaultdict

ROOT = pathlib.Path(__file__).resolve().parent.parent

# The test files of the flight code (component/ and port/): each of their tests must verify a
# requirement. Paths relative to the repository, fnmatch patterns; each must match a file.
FLIGHT_TESTS = [
    "tests/flight/*.cpp",
    "tests/component_*_test.cpp",
    "tests/config_*_test.cpp",
    "tests/rotor_*_test.cpp",
    "tests/arctangent_test.cpp",
    "tests/attitude_edges_test.cpp",
    "tests/exact_step_check_test.cpp",
    "tests/gyro_model_test.cpp",
    "tests/gyro_model_*_test.cpp",
    "tests/status_text_test.cpp",
    "tests/report_sample_test.cpp",
    "tests/link_*_test.cpp",
    "tests/rate_group_test.cpp",
    "tests/no_heap_test.cpp",
]

METHODS = ("test", "analysis", "inspection")
ID_RE = re.compile(r"\b[A-Z]+-[0-9]+\b")
HEADING_RE = re.compile(r"^### ([A-Z]+-[0-9]+)\s*$")
RUN_RE = re.compile(r"^\[ RUN      \] (\S+)")
END_RE = re.compile(r"^\[ +(OK|FAILED|SKIPPED) +\] (\S+)")
SOURCE_RE = re.compile(r"^\[ SOURCE   \] (\S+)")
VERIFIES_RE = re.compile(r"^\[ VERIFIES \] (.*)$")


class Requirement:
    def __init__(self, rid, line):
        self.id = rid
        self.line = line
        self.title = ""
        self.statement = ""
        self.rationale = ""
        self.verification = ""
        self.methods = []
        self.ctests = []  # ctests (not GoogleTests) named by the requirement


def parse_requirements(path):
    """The requirements of docs/requirements.md, in order, and the problems of their form."""
    reqs, problems = [], []
    current, block = None, []

    def close():
        if current is None:
            return
        text = "\n".join(block)
        m = re.search(r"\*\*(.+?)\*\*", text, re.S)
        current.title = " ".join(m.group(1).split()) if m else ""
        statement = text.split("\n- Rationale:")[0]
        current.statement = " ".join(statement.split())
        for key in ("Rationale", "Verification"):
            m = re.search(r"^- " + key + r":(.*?)(?=^- |\Z)", text, re.S | re.M)
            setattr(current, key.lower(), " ".join(m.group(1).split()) if m else "")
        v = current.verification
        current.methods = [w for w in METHODS if re.search(r"(^|[;,] *)" + w + r"\b", v)]
        current.ctests = re.findall(r"ctest `([^`]+)`", v)
        where = f"{path.name}:{current.line}: {current.id}"
        if not current.title:
            problems.append(f"{where}: no bold title")
        if " shall " not in f" {current.statement} ":
            problems.append(f"{where}: the statement has no \"shall\"")
        if not current.rationale:
            problems.append(f"{where}: no \"- Rationale:\" line")
        if not current.methods:
            problems.append(f"{where}: no verification method (test, analysis, inspection)")
        for method in ("analysis", "inspection"):
            if method in current.methods:
                m = re.search(method + r":(.*?)(?:; (?:test|analysis|inspection)\b|$)", v)
                evidence = m.group(1).strip() if m else ""
                if not evidence:
                    problems.append(f"{where}: the {method} names no evidence (\"{method}: ...\")")
                for ref in re.findall(r"`([^`]+)`", evidence):
                    if ("/" in ref or re.search(r"\.(md|sh|py|cpp|hpp|cmake|txt)$", ref)) and " " not in ref:
                        if not (ROOT / ref).exists():
                            problems.append(f"{where}: its evidence `{ref}` does not exist")
        reqs.append(current)

    for n, line in enumerate(path.read_text().splitlines(), 1):
        m = HEADING_RE.match(line)
        if m:
            close()
            current, block = Requirement(m.group(1), n), []
        elif line.startswith("## ") or line.startswith("# "):
            close()
            current, block = None, []
        elif current is not None:
            block.append(line)
    close()
    seen = set()
    for r in reqs:
        if r.id in seen:
            problems.append(f"{path.name}:{r.line}: {r.id} is used twice")
        seen.add(r.id)
    return reqs, problems


class TestRun:
    """One test as the run saw it: a GoogleTest (name Suite.Test) or another ctest."""

    def __init__(self, name, ctest):
        self.name = name
        self.ctest = ctest
        self.source = None
        self.verifies = []
        self.result = "not run"
        self.gtest = False  # found by its GoogleTest markers


def ctest_result(case):
    status = case.get("status", "")
    if status == "run":
        return "passed"
    if status in ("fail", "failed"):
        return "failed"
    if status in ("disabled", "notrun", "skipped"):
        return "skipped"
    return status or "unknown"


def parse_junit(path):
    """Every test of the run: GoogleTests by their markers in each ctest's output."""
    tests = []
    for case in ET.parse(path).getroot().iter("testcase"):
        ctest = case.get("name")
        out_el = case.find("system-out")
        out = (out_el.text or "") if out_el is not None else ""
        status = ctest_result(case)
        gtests, current = [], None
        for line in out.splitlines():
            m = RUN_RE.match(line)
            if m:
                current = TestRun(m.group(1), ctest)
                current.result = None
                current.gtest = True
                gtests.append(current)
                continue
            if current is None:
                continue
            m = SOURCE_RE.match(line)
            if m:
                # Relative to the repository; a build through ccache (base_dir) names some
                # sources relative to the build directory: "../../../tests/x_test.cpp".
                current.source = re.sub(r"^(\.\./)+", "", m.group(1))
                continue
            m = VERIFIES_RE.match(line)
            if m:
                current.verifies += m.group(1).split()
                continue
            m = END_RE.match(line)
            if m and m.group(2) == current.name:
                current.result = {"OK": "passed", "FAILED": "failed", "SKIPPED": "skipped"}[m.group(1)]
                current = None
        if not gtests:
            t = TestRun(ctest, ctest)
            t.result = status
            tests.append(t)
            continue
        for t in gtests:
            # One GoogleTest per ctest (gtest_discover_tests): ctest's verdict is the test's
            # (its output may be cut short); several: each by its own end marker.
            if len(gtests) == 1 or t.result is None:
                t.result = status if (len(gtests) == 1 or status != "passed") else "passed"
        tests.extend(gtests)
    return tests


def group_name(name):
    """Typed and parameterised instances as one test: NoHeap/0.X and NoHeap/1.X are NoHeap/*.X."""
    return re.sub(r"/\d+(?=\.|$)", "/*", name)


def combined(results):
    for r in ("failed", "not run", "skipped"):
        if r in results:
            return r
    return "passed"


def is_flight_test(source):
    return source is not None and any(fnmatch.fnmatch(source, p) for p in FLIGHT_TESTS)


def anchor(rid):
    return f"requirements.md#{rid.lower()}"


def render(reqs, tests_by_group, by_req, junit_name):
    total = len(reqs)
    by_method = defaultdict(int)
    for r in reqs:
        by_method["test" if "test" in r.methods else r.methods[0] if r.methods else "none"] += 1
    verified = sum(1 for r in reqs if "test" in r.methods and any(
        tests_by_group[g]["result"] == "passed" for g in by_req[r.id]))
    flight = [g for g, t in tests_by_group.items() if is_flight_test(t["source"])]
    lines = [
        "# Traceability: requirements to tests",
        "",
        "**Generated** by `scripts/trace.py` from the test run (ctest's JUnit file, "
        f"`{junit_name}`) and [requirements.md](requirements.md); do not edit by hand: "
        "`scripts/test.sh` fails when this file is not what the run generates.",
        "",
        f"{total} requirements: {by_method['test']} verified by test ({verified} with a passing test in "
        f"this run), {by_method['analysis']} by analysis and {by_method['inspection']} by inspection "
        "alone. "
        f"{sum(1 for t in tests_by_group.values() if t['verifies'])} tests name a requirement, "
        f"{len(flight)} of them in the flight code's test files. Typed and parameterised tests count "
        "once (`Suite/*.Name`: every instance).",
        "",
        "## Requirements to tests",
        "",
        "| requirement | title | method | tests | result |",
        "|---|---|---|---|---|",
    ]
    for r in reqs:
        names = sorted(by_req[r.id])
        results = [tests_by_group[g]["result"] for g in names]
        if names:
            result = f"{combined(results)} ({len(names)})"
        elif "test" in r.methods:
            result = "**no test**"
        else:
            result = "–"
        method = ", ".join(r.methods)
        cell = "<br>".join(f"`{g}`" for g in names) if names else "–"
        lines.append(f"| [{r.id}]({anchor(r.id)}) | {r.title} | {method} | {cell} | {result} |")
    lines += ["", "## Tests to requirements", ""]
    by_source = defaultdict(list)
    for g, t in tests_by_group.items():
        if t["verifies"] or is_flight_test(t["source"]):
            by_source[t["source"] or "(ctest)"].append(g)
    for source in sorted(by_source):
        lines += [f"### `{source}`", "", "| test | requirements | result |", "|---|---|---|"]
        for g in sorted(by_source[source]):
            t = tests_by_group[g]
            ids = ", ".join(f"[{i}]({anchor(i)})" for i in sorted(t["verifies"], key=id_key)) or "**none**"
            lines.append(f"| `{g}` | {ids} | {t['result']} |")
        lines.append("")
    return "\n".join(lines)


def id_key(rid):
    group, n = rid.rsplit("-", 1)
    return (group, int(n))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--requirements", default=str(ROOT / "docs/requirements.md"))
    ap.add_argument("--junit", default=str(ROOT / "build/host/junit.xml"))
    ap.add_argument("--output", default=str(ROOT / "docs/traceability.md"))
    ap.add_argument("--compare", help="a committed traceability.md that must equal the output")
    args = ap.parse_args()

    reqs, problems = parse_requirements(pathlib.Path(args.requirements))
    known = {r.id for r in reqs}
    junit = pathlib.Path(args.junit)
    if not junit.is_file():
        print(f"trace: no test result {junit} (run the suite first: scripts/test.sh)", file=sys.stderr)
        return 2
    tests = parse_junit(junit)

    for pattern in FLIGHT_TESTS:
        if not list(ROOT.glob(pattern)):
            problems.append(f"trace.py: FLIGHT_TESTS pattern {pattern} matches no file")

    # Tests by group name (typed instances as one), with what they verify and their result.
    tests_by_group = {}
    ctest_names = {}
    for t in tests:
        ctest_names[t.ctest] = t
        g = group_name(t.name)
        entry = tests_by_group.setdefault(g, {"source": t.source, "verifies": set(), "results": []})
        entry["verifies"] |= set(t.verifies)
        entry["results"].append(t.result)
        entry["source"] = entry["source"] or t.source
    for entry in tests_by_group.values():
        entry["result"] = combined(entry["results"])

    by_req = defaultdict(set)
    for g, entry in tests_by_group.items():
        for rid in entry["verifies"]:
            if rid not in known:
                problems.append(f"{g} ({entry['source']}): names {rid}, which is no requirement")
            else:
                by_req[rid].add(g)
    for r in reqs:
        for name in r.ctests:
            if name not in ctest_names:
                problems.append(f"{r.id}: names ctest {name}, which did not run")
                continue
            g = group_name(ctest_names[name].name)
            by_req[r.id].add(g)
            tests_by_group[g]["verifies"].add(r.id)

    for g, entry in sorted(tests_by_group.items()):
        if is_flight_test(entry["source"]) and not entry["verifies"]:
            problems.append(f"{g} ({entry['source']}): a test of the flight code that verifies no requirement")
    for t in tests:
        if t.gtest and t.source is None:
            problems.append(f"{t.name} (ctest {t.ctest}): reported no source file (tests/support/trace_main.cpp)")
    for r in reqs:
        if "test" in r.methods and not any(tests_by_group[g]["result"] == "passed" for g in by_req[r.id]):
            problems.append(f"{r.id}: verified by test, but no test that verifies it passed")

    text = render(reqs, tests_by_group, by_req, junit.name) + "\n"
    out = pathlib.Path(args.output)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)
    if args.compare:
        committed = pathlib.Path(args.compare)
        if not committed.is_file() or committed.read_text() != text:
            problems.append(f"{args.compare} is not what this run generates ({out}): "
                            f"run scripts/trace.py and commit it")

    for p in problems:
        print(f"trace: {p}", file=sys.stderr)
    n_tests = sum(1 for e in tests_by_group.values() if e["verifies"])
    print(f"trace: {len(reqs)} requirements, {n_tests} tests naming them, {len(problems)} problems; "
          f"wrote {out}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
