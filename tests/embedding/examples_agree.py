"""docs/embedding.md's examples each run the report's sample and print
    report sample: N steps, gimbal pitch P yaw Y rad
This runs the C++ example (the reference) and one other, and checks that they took the same
steps and agree on the gimbal angles within the tolerance.

    examples_agree.py --tolerance 1e-12 REFERENCE -- COMMAND [ARG...]
"""

import argparse
import re
import subprocess
import sys

LINE = re.compile(r"report sample: (\d+) steps, gimbal pitch (\S+) yaw (\S+) rad")


def run(command):
    out = subprocess.run(command, check=True, capture_output=True, text=True, timeout=300).stdout
    m = LINE.search(out)
    if not m:
        sys.exit(f"{command[0]}: no result line in its output:\n{out}")
    print(m.group(0))
    return int(m.group(1)), float(m.group(2)), float(m.group(3))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--tolerance", type=float, required=True)
    parser.add_argument("reference")
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    steps, pitch, yaw = run([args.reference])
    other_steps, other_pitch, other_yaw = run(command)
    diff = max(abs(pitch - other_pitch), abs(yaw - other_yaw))
    print(f"largest difference {diff:.3g} rad")
    if other_steps != steps or not diff <= args.tolerance:
        sys.exit(f"the example disagrees with the C++ example (tolerance {args.tolerance:g} rad)")


if __name__ == "__main__":
    main()
