"""The module's default OpenMP wait policy (issue 48): passive, as in the `lfsp` executable, unless the user set one.

libgomp prints the spin count it settled on when OMP_DISPLAY_ENV=verbose; a fresh interpreter is needed because
libgomp reads its settings once, when the extension loads it.
"""

import os
import re
import subprocess
import sys


def spin_count_after_import(**variables):
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    env.update(variables, OMP_DISPLAY_ENV="verbose")
    done = subprocess.run([sys.executable, "-c", "import lfsp"], env=env, capture_output=True, text=True, check=True)
    match = re.search(r"GOMP_SPINCOUNT = '(\d+)'", done.stdout + done.stderr)
    assert match, done.stderr
    return match.group(1)


def test_passive_by_default():
    assert spin_count_after_import() == "0"


def test_the_users_choice_wins():
    assert spin_count_after_import(OMP_WAIT_POLICY="active") == "30000000000"
    assert spin_count_after_import(GOMP_SPINCOUNT="4321") == "4321"
