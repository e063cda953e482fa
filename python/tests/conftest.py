"""Shared fixtures: where the CLI, the samples and the shared real data are (CTest sets the environment)."""

import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("LFSP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SHARED_DATA = os.environ.get("LFSP_SHARED_DATA", os.path.join(SOURCE_DIR, "..", "shared", "data"))
IDEAL_SAMPLE = os.path.join(SOURCE_DIR, "samples", "ideal", "ideal.h5")
MINI_ILLUM = os.path.join(SOURCE_DIR, "samples", "mini-illum")
ANTINOUS = os.path.join(SHARED_DATA, "hci", "antinous")


def lfsp_binary() -> str:
    binary = os.environ.get("LFSP_BINARY")
    if not binary:
        pytest.fail("LFSP_BINARY is not set: run through ctest, or set it to build/apps/lfsp")
    return binary


def run_cli(*arguments: str, expect_status: int = 0) -> subprocess.CompletedProcess:
    """Runs `lfsp -q ARGS...`; fails the test unless it exits with expect_status."""
    result = subprocess.run([lfsp_binary(), "-q", *map(str, arguments)], capture_output=True, text=True)
    assert result.returncode == expect_status, f"lfsp {' '.join(map(str, arguments))}: {result.stderr}"
    return result


def cli_error_message(*arguments: str) -> str:
    """The one-line message `lfsp` prints for bad input, without its 'lfsp: error: ' prefix."""
    stderr = run_cli(*arguments, expect_status=2).stderr.strip()
    assert stderr.startswith("lfsp: error: "), stderr
    return stderr[len("lfsp: error: ") :]


def require(path: str) -> str:
    """The path, which must exist. Shared real data may be absent (a clone without ../shared/data): its tests skip,
    as the C++ suites' LFSP_REQUIRE_SHARED_DATA do; anything else missing fails."""
    if not os.path.exists(path):
        if os.path.abspath(path).startswith(os.path.abspath(SHARED_DATA) + os.sep):
            pytest.skip(f"{path}: missing (shared test data): real-data test skipped")
        pytest.fail(f"{path}: missing")
    return path
