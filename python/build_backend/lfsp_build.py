"""lfsp's PEP 517 build backend: `pip install .` builds lfsp through CMake and installs what CMake installs.

Why a backend of our own: the package is CMake's build (the C++ stage libraries, the `lfsp` command, the pybind11
extension, the man pages), and it must install offline from Debian's packages (`pip install --no-build-isolation .`).
Debian bookworm ships no maintained CMake build backend: scikit-build-core is not packaged there, python3-scikit-build
is not either (and is the old setuptools-based one), and meson-python builds Meson projects only. So this file,
standard library only, does what such a backend would:

  1. configure the build folder if it is not configured yet (Release, no tests or benchmarks, this interpreter);
  2. build the targets a user installs: lfsp, _lfsp and the man pages;
  3. `cmake --install` them (components cli and python) into a staging folder;
  4. pack the staged files into a wheel: the package lfsp/ (the extension inside), the command as a script
     (<venv>/bin/lfsp) and the man pages as data (<venv>/share/man/man1).

The build folder is `build-pip` in the source tree ([tool.lfsp-build] in pyproject.toml), or the one given by
`--config-settings build-dir=PATH` or LFSP_BUILD_DIR=PATH: an already-configured folder (e.g. `make`'s build/) is
reused as it is, so nothing is compiled twice. CMAKE_BUILD_PARALLEL_LEVEL (or `--config-settings jobs=N`) sets the
parallel jobs. The version is the one CMake decided (cmake/LfspVersion.cmake), read from <build>/lfsp_version.txt.
"""

import base64
import hashlib
import os
import stat
import subprocess
import sys
import sysconfig
import tempfile
import zipfile
from pathlib import Path

try:
    import tomllib
except ImportError:  # Python < 3.11
    sys.exit("lfsp_build: building lfsp needs Python 3.11 or later (tomllib reads pyproject.toml)")

_SOURCE = Path(__file__).resolve().parents[2]


def _log(message):
    print(f"lfsp_build: {message}", file=sys.stderr, flush=True)


def _run(command, **kwargs):
    _log(" ".join(str(part) for part in command))
    subprocess.run([str(part) for part in command], check=True, **kwargs)


def _project():
    with open(_SOURCE / "pyproject.toml", "rb") as file:
        return tomllib.load(file)


def _setting(config_settings, key, environment):
    if config_settings and config_settings.get(key):
        return config_settings[key]
    return os.environ.get(environment) or None


def _build_folder(config_settings):
    chosen = _setting(config_settings, "build-dir", "LFSP_BUILD_DIR")
    if chosen is None:
        chosen = _project().get("tool", {}).get("lfsp-build", {}).get("build-dir", "build-pip")
    return (_SOURCE / chosen).resolve()


def _cache_value(build, name):
    for line in (build / "CMakeCache.txt").read_text().splitlines():
        if line.startswith(name + ":"):
            return line.split("=", 1)[1]
    return None


def _build_and_stage(build, staging, config_settings):
    if not (build / "CMakeCache.txt").exists():
        _run(["cmake", "-S", _SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DLFSP_BUILD_TESTS=OFF",
              "-DLFSP_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}"])
    if _cache_value(build, "LFSP_BUILD_PYTHON") == "OFF":
        raise RuntimeError(f"{build} is configured with LFSP_BUILD_PYTHON=OFF: no Python module to install")
    targets = ["lfsp", "_lfsp"]
    if _cache_value(build, "LFSP_BUILD_MAN") != "OFF":
        targets.append("lfsp_man_pages")
    jobs = _setting(config_settings, "jobs", "CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    _run(["cmake", "--build", build, "--target", *targets, "--parallel", jobs])
    # DESTDIR keeps even an absolute LFSP_PYTHON_INSTALL_DIR inside the staging folder.
    environment = dict(os.environ, DESTDIR=str(staging))
    for component in ("cli", "python"):
        _run(["cmake", "--install", build, "--prefix", "/prefix", "--component", component], env=environment,
             stdout=sys.stderr)


def _one(staging, pattern, what):
    found = sorted(staging.glob(pattern))
    if len(found) != 1:
        raise RuntimeError(f"the staged install has {len(found)} {what} ({pattern}), expected one")
    return found[0]


def _wheel_tag():
    interpreter = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{interpreter}-{interpreter}-{platform}"


def _metadata(version):
    project = _project()["project"]
    lines = [
        "Metadata-Version: 2.1",
        f"Name: {project['name']}",
        f"Version: {version}",
        f"Summary: {project['description']}",
        f"Requires-Python: {project['requires-python']}",
    ]
    lines += [f"Author: {author['name']}" for author in project.get("authors", [])]
    lines.append(f"Keywords: {','.join(project.get('keywords', []))}")
    lines += [f"Classifier: {classifier}" for classifier in project.get("classifiers", [])]
    lines += [f"Requires-Dist: {requirement}" for requirement in project.get("dependencies", [])]
    lines.append("Description-Content-Type: text/markdown")
    return "\n".join(lines) + "\n\n" + (_SOURCE / project["readme"]).read_text()


class _Wheel:
    """A wheel being written: each file's hash goes into RECORD."""

    def __init__(self, path):
        self._zip = zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED)
        self._records = []

    def add(self, name, data, executable=False):
        info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        # A regular file's mode: pip makes a file executable only when the mode says it is a regular file.
        info.external_attr = (stat.S_IFREG | (0o755 if executable else 0o644)) << 16
        self._zip.writestr(info, data)
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        self._records.append(f"{name},sha256={digest},{len(data)}")

    def close(self, record_name):
        self._records.append(f"{record_name},,")
        self._zip.writestr(zipfile.ZipInfo(record_name, date_time=(1980, 1, 1, 0, 0, 0)),
                           "\n".join(self._records) + "\n")
        self._zip.close()


def get_requires_for_build_wheel(config_settings=None):
    return []  # cmake, a C++ compiler and the libraries come from the system (tools/bootstrap)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build = _build_folder(config_settings)
    with tempfile.TemporaryDirectory(prefix="lfsp-wheel-") as temporary:
        staging = Path(temporary)
        _build_and_stage(build, staging, config_settings)
        version = (build / "lfsp_version.txt").read_text().strip()
        package = _one(staging, "**/lfsp/__init__.py", "lfsp packages").parent
        extension = _one(package, "_lfsp*.so", "extension modules")
        if not extension.name.endswith(sysconfig.get_config_var("EXT_SUFFIX")):
            raise RuntimeError(f"{build} built {extension.name} for another Python than {sys.executable} "
                               f"(expected *{sysconfig.get_config_var('EXT_SUFFIX')}); give another build-dir")
        command = _one(staging, "**/bin/lfsp", "lfsp commands")

        dist_info = f"lfsp-{version}.dist-info"
        data = f"lfsp-{version}.data"
        wheel_name = f"lfsp-{version}-{_wheel_tag()}.whl"
        wheel = _Wheel(Path(wheel_directory) / wheel_name)
        for path in sorted(package.rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts:
                wheel.add(f"lfsp/{path.relative_to(package).as_posix()}", path.read_bytes())
        wheel.add(f"{data}/scripts/lfsp", command.read_bytes(), executable=True)
        for page in sorted(staging.glob("**/man1/*.1")):
            wheel.add(f"{data}/data/share/man/man1/{page.name}", page.read_bytes())
        wheel.add(f"{dist_info}/METADATA", _metadata(version).encode())
        wheel.add(f"{dist_info}/WHEEL", (f"Wheel-Version: 1.0\nGenerator: lfsp_build\nRoot-Is-Purelib: false\n"
                                         f"Tag: {_wheel_tag()}\n").encode())
        wheel.close(f"{dist_info}/RECORD")
    _log(f"wrote {wheel_name}")
    return wheel_name
