"""Bad input raises lfsp.Error with the command line's message; keywords are checked; Ctrl-C stops long work; the
GIL is released; progress reaches a callback."""

import os
import signal
import subprocess
import sys
import threading
import time

import numpy
import pytest

import lfsp
from conftest import ANTINOUS, IDEAL_SAMPLE, cli_error_message, require


def test_missing_file_gives_the_command_lines_message(tmp_path):
    missing = str(tmp_path / "nothing.h5")
    with pytest.raises(lfsp.Error) as raised:
        lfsp.read(missing)
    assert str(raised.value) == cli_error_message("info", missing)


def test_truncated_bundle_gives_the_command_lines_message(tmp_path):
    truncated = tmp_path / "truncated.h5"
    with open(IDEAL_SAMPLE, "rb") as source:
        truncated.write_bytes(source.read(4096))
    with pytest.raises(lfsp.Error) as raised:
        lfsp.read(truncated)
    assert str(raised.value) == cli_error_message("depth", str(truncated), "--out", str(tmp_path / "d.pfm"))
    assert "\n" not in str(raised.value)


def test_garbage_capture_gives_the_command_lines_message(tmp_path):
    garbage = tmp_path / "capture.lfp"
    garbage.write_bytes(b"\x89LFP" + os.urandom(2000))
    with pytest.raises(lfsp.Error) as raised:
        lfsp.decode(garbage)
    assert str(raised.value) == cli_error_message("decode", str(garbage), "--out", str(tmp_path / "out.h5"))


def test_an_unknown_keyword_is_a_type_error_as_in_python():
    lf = lfsp.read(IDEAL_SAMPLE)
    with pytest.raises(TypeError, match=r"segment\(\) got an unexpected keyword argument 'lambda_q'"):
        lfsp.segment(lf, lambda_q=1.0)


def test_a_refused_value_names_the_keyword():
    lf = lfsp.read(IDEAL_SAMPLE)
    with pytest.raises(lfsp.Error, match="labels") as raised:
        lfsp.depth(lf, labels=2)  # --labels takes 3..1024
    assert "--" not in str(raised.value)
    with pytest.raises(lfsp.Error, match="dmin"):
        lfsp.depth(lf, dmin=-1.0)  # only one end of the range
    with pytest.raises(lfsp.Error, match="exactly one way"):
        lfsp.recolor(lf, label_ids=[1], at=[(3, 4)])
    with pytest.raises(lfsp.Error, match="space"):
        lfsp.recolor(lf, label_ids=[1], space="cmyk")


def test_help_says_what_the_command_line_help_says():
    doc = lfsp.segment.__doc__
    assert "lambda_p (FLOAT, default" in doc and "Position weight lambda_p (Table II)" in doc
    assert "views (INT:NONNEGATIVE, default 0)" in doc
    assert "dmin" in lfsp.depth.__doc__ and "Smallest disparity" in lfsp.depth.__doc__
    assert "no_noise (flag" in lfsp.simulate.__doc__


def test_progress_reaches_a_callback():
    steps = []
    lfsp.set_progress(lambda label, done, total: steps.append((label, done, total)))
    try:
        lfsp.depth(lfsp.read(IDEAL_SAMPLE))
    finally:
        lfsp.set_progress(None)
    assert steps and all(label == "depth" for label, _, _ in steps)
    assert steps[-1][1] == steps[-1][2]  # it finished


def test_an_exception_in_the_callback_stops_the_work():
    def refuse(label, done, total):
        raise RuntimeError("stop here")

    lfsp.set_progress(refuse)
    try:
        with pytest.raises(RuntimeError, match="stop here"):
            lfsp.depth(lfsp.read(IDEAL_SAMPLE))
    finally:
        lfsp.set_progress(None)


def test_long_work_releases_the_gil():
    lf = lfsp.read(require(ANTINOUS))
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    counter = threading.Thread(target=count)
    counter.start()
    started = time.monotonic()
    try:
        lfsp.depth(lf, labels=16)
    finally:
        done.set()
        counter.join()
    elapsed = time.monotonic() - started
    during = [t for t in ticks if started < t < started + elapsed]
    # A thread blocked by the GIL would not tick at all while depth runs.
    assert len(during) > 0.3 * elapsed / 0.01


INTERRUPTED_SCRIPT = """
import sys, time, lfsp
lf = lfsp.read(sys.argv[1])
print("ready", flush=True)
started = time.monotonic()
try:
    lfsp.segment(lf, iterations=1000, convergence=0)
except KeyboardInterrupt:
    print(f"interrupted after {time.monotonic() - started:.2f} s", flush=True)
    sys.exit(3)
"""


def test_ctrl_c_stops_long_work_cleanly(tmp_path):
    process = subprocess.Popen([sys.executable, "-c", INTERRUPTED_SCRIPT, require(ANTINOUS)], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env=os.environ)
    assert process.stdout.readline().strip() == "ready"
    time.sleep(3.0)  # well into the segmentation
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    stdout, stderr = process.communicate(timeout=60)
    stopped = time.monotonic() - sent
    assert process.returncode == 3, stderr
    assert "interrupted after" in stdout
    assert stopped < 15.0  # stopped at the next iteration, not after 1000 of them
