#!/usr/bin/env bash
# The .deb as a user gets it: built by CPack from BUILD_DIR (nothing is compiled), unpacked with dpkg -x into a
# throw-away root, and run from there without LD_LIBRARY_PATH.
# Usage: deb_test.sh BUILD_DIR PYTHON
set -euo pipefail
build=$1 python=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/lfsp-deb-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

(cd "$build" && cpack -G DEB -B "$work/staging" -D "CPACK_OUTPUT_FILE_PREFIX=$work/packages" > "$work/cpack.log") || { cat "$work/cpack.log"; exit 1; }
deb=$(find "$work/packages" -maxdepth 1 -name 'lfsp_*.deb')
[ -n "$deb" ] || { echo "cpack wrote no .deb" >&2; cat "$work/cpack.log"; exit 1; }
echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KiB"
dpkg-deb --field "$deb" Package Version Depends
root=$work/root
dpkg-deb -x "$deb" "$root"

lfsp=$root/usr/bin/lfsp
version=$("$lfsp" --version)
echo "$version"
expected="lfsp $(cat "$build/lfsp_version.txt")"
[ "$version" = "$expected" ] || { echo "--version says '$version', the build '$expected'" >&2; exit 1; }
[ "$(dpkg-deb --field "$deb" Version)" = "${expected#lfsp }" ] || { echo "the package's version differs" >&2; exit 1; }
"$lfsp" info "$root/usr/share/lfsp/samples/mini-illum/capture.LFR"
for page in lfsp lfsp-decode lfsp-pipeline lfsp-evaluate-depth; do
  [ -f "$root/usr/share/man/man1/$page.1" ] || { echo "the package has no $page(1)" >&2; exit 1; }
done
[ -f "$root/usr/share/lfsp/workflow/Snakefile" ] || { echo "the package has no workflow" >&2; exit 1; }
site=$(dirname "$(dirname "$(find "$root/usr/lib" -path '*/lfsp/__init__.py')")")
(cd "$work" && PYTHONPATH="$site" "$python" -c 'import lfsp, sys; assert lfsp.__file__.startswith(sys.argv[1]); print("module", lfsp.__version__)' "$root")
echo "deb: command, sample, man pages, workflow and module work from the unpacked package"
