#!/bin/sh
# `cmake --install` puts a package that imports and works. Staged under DESTDIR so that nothing leaves the build.
# Usage: check_install.sh BUILD_DIR STAGING_DIR SITE_PACKAGES PYTHON
set -eu
build=$1 staged=$2 site=$3 python=$4
rm -rf "$staged"
DESTDIR="$staged" cmake --install "$build" > /dev/null
find "$staged" -path "*/bin/lfsp" -type f | grep -q . || { echo "the lfsp executable was not installed" >&2; exit 1; }
cd /
PYTHONPATH="$staged$site" "$python" - "$staged" <<'PY'
import sys
import lfsp
assert lfsp.__file__.startswith(sys.argv[1]), lfsp.__file__
print(lfsp.simulate(scene="planes", size="32x32", views=3).light_field)
PY
