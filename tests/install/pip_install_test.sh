#!/usr/bin/env bash
# `pip install .` as a user does it, offline: a fresh venv (numpy from Debian through --system-site-packages), the
# source tree installed with --no-build-isolation through the in-tree backend, which reuses BUILD_DIR.
# Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
set -euo pipefail
source_dir=$1 build=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/lfsp-pip-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

"$python" -m venv --system-site-packages "$work/venv"
venv=$work/venv
# --no-index: offline, as the tests must be; numpy is already there from Debian.
CMAKE_BUILD_PARALLEL_LEVEL=2 "$venv/bin/python" -m pip install --no-build-isolation --no-index --quiet \
  --config-settings "build-dir=$build" "$source_dir"

cd "$work"  # nowhere near the source or build trees, so only the installed package can be imported
"$venv/bin/python" - "$venv" "$source_dir/samples/ideal/ideal.h5" <<'PY'
import importlib.metadata
import sys

import lfsp

venv, sample = sys.argv[1:]
assert lfsp.__file__.startswith(venv), lfsp.__file__
assert importlib.metadata.version("lfsp") == lfsp.__version__, (importlib.metadata.version("lfsp"), lfsp.__version__)
light_field = lfsp.read(sample)
refocused = lfsp.refocus(light_field, 0.5)
print(f"lfsp {lfsp.__version__}: {light_field}, refocused to {refocused.shape}")
PY

installed="$venv/bin/lfsp"
[ -x "$installed" ] || { echo "pip did not install the lfsp command" >&2; exit 1; }
version=$("$installed" --version)
expected=$("$venv/bin/python" -c 'import lfsp; print("lfsp", lfsp.__version__)')
[ "$version" = "$expected" ] || { echo "lfsp --version says '$version', the module '$expected'" >&2; exit 1; }
"$installed" info "$source_dir/samples/ideal/ideal.h5"
[ -f "$venv/share/man/man1/lfsp.1" ] && [ -f "$venv/share/man/man1/lfsp-decode.1" ] ||
  { echo "pip did not install the man pages" >&2; exit 1; }
echo "pip install: $version, module, command and man pages installed"
