"""Ctrl-C in the long calls: run_sil and run_campaign, started in a child interpreter, raise
KeyboardInterrupt soon after SIGINT (run_sil within one signal-check period and a tick,
run_campaign once the runs under way finish), leave no file behind in the working directory
or $TMPDIR (as gyro_campaign leaves none on SIGINT), and leave the module usable."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import gyro

CHILD = textwrap.dedent("""
    import signal, sys, time
    signal.signal(signal.SIGINT, signal.default_int_handler)  # even if started with SIGINT ignored
    import gyro
    kind, source = sys.argv[1], sys.argv[2]
    print("started", flush=True)
    try:
        if kind == "sil":
            gyro.run_sil(source, ticks=1_500_000)  # about 25 s of run; its bound is under 1 GiB
        else:
            gyro.run_campaign({"base": source, "runs": 100_000, "seed": 1}, threads=2)  # about an hour
    except KeyboardInterrupt:
        print("interrupted", repr(time.monotonic()), flush=True)
        # The module still works after the interrupt.
        print("after", len(gyro.run_sil(source, ticks=10)), flush=True)
        sys.exit(3)
    print("finished", flush=True)
""")


def interrupt_child(tmp_path, source_dir, kind, wait_s=20.0):
    """Starts the child, sends SIGINT 0.5 s after it starts the call; returns (rc, lines, delay)."""
    work = tmp_path / "work"
    tmp = tmp_path / "tmp"
    work.mkdir()
    tmp.mkdir()
    env = dict(os.environ, TMPDIR=str(tmp))
    child = subprocess.Popen([sys.executable, "-c", CHILD, kind, str(source_dir / "scenarios" / "seeker_slew.json")],
                             cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(0.5)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=wait_s)
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        pytest.fail(f"{kind}: no KeyboardInterrupt within {wait_s} s of SIGINT")
    lines = out.split("\n")
    assert child.returncode == 3, (child.returncode, out, err)
    assert lines[0].startswith("interrupted"), out
    delay = float(lines[0].split()[1]) - sent
    assert lines[1] == "after 11", out
    assert sorted(os.listdir(work)) == [] and sorted(os.listdir(tmp)) == []  # nothing written, nothing left
    print(f"{kind}: KeyboardInterrupt {delay * 1e3:.1f} ms after SIGINT")
    return delay


def test_given_a_long_sil_run_when_sigint_arrives_then_keyboard_interrupt_within_a_tick(tmp_path, source_dir):
    delay = interrupt_child(tmp_path, source_dir, "sil")
    # One check period (20 ms) and a tick (about 20 us), with room for a loaded machine.
    assert 0.0 <= delay < 0.5, delay


def test_given_a_long_campaign_when_sigint_arrives_then_keyboard_interrupt_within_a_run(tmp_path, source_dir):
    delay = interrupt_child(tmp_path, source_dir, "campaign")
    # The runs under way finish first: a run of seeker_slew takes about 25 ms.
    assert 0.0 <= delay < 1.0, delay


def test_given_a_run_on_another_thread_then_it_completes_and_the_caller_keeps_running(source_dir):
    # Signal handlers run on the main thread only: the periodic check is a no-op elsewhere,
    # and the GIL is free while the run computes.
    result = {}
    worker = threading.Thread(target=lambda: result.update(
        sil=len(gyro.run_sil(source_dir / "scenarios" / "seeker_slew.json", ticks=20_000))))
    worker.start()
    spins = 0
    while worker.is_alive():
        spins += 1
        time.sleep(0.001)
    worker.join()
    assert result == {"sil": 20_001}
    assert spins > 10  # about 0.3 s of run: the main thread ran meanwhile, not after
