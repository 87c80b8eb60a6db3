"""The PEP 517 build backend of `pip install .` (pyproject.toml): CMake builds
the module `quadra` and the libquadra.so it links, and this file packs them
into a wheel for the running interpreter. Standard library only: Debian 12
has no scikit-build-core, and with `requires = []` pip's isolated build
environment needs nothing from an index, so the install works offline.

The wheel holds

    quadra.cpython-311-x86_64-linux-gnu.so   its RUNPATH set to $ORIGIN/quadra.libs
    quadra.libs/libquadra.so.0.1             under the name the module asks for
    quadra-0.1.0.dist-info/                  METADATA, WHEEL, RECORD

so it works wherever pip puts site-packages (a venv, --user, --target);
the other libraries (oneTBB, OpenEXR, libpng, libjpeg) are Debian's.

The build directory is a fresh temporary one, removed afterwards, unless
the config setting `build-dir` (pip install --config-settings build-dir=DIR)
or the environment's QUADRA_WHEEL_BUILD_DIR names one. A DIR that CMake has
configured already is only built (the PipInstall test reuses the test
suite's tree this way, so its options are left as they are); any other DIR
is configured like the temporary one and kept for the next install.
"""
import base64
import hashlib
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import tomllib
import zipfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
# The module and the library it links; the CLI, the tests and the benchmarks
# are not built.
TARGETS = ("quadra_python", "quadra_shared")
LIBS = "quadra.libs"  # auditwheel's name for a wheel's own libraries
# Written by python/CMakeLists.txt: what the wheel packs, as CMake names it.
WHEEL_FILES = "python/wheel_files.txt"
# A fixed time for every member, so that one build gives one wheel.
ZIP_TIME = (1980, 1, 1, 0, 0, 0)


class BuildError(Exception):
    pass


def get_requires_for_build_wheel(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    chosen = (config_settings or {}).get("build-dir") or os.environ.get("QUADRA_WHEEL_BUILD_DIR")
    with tempfile.TemporaryDirectory(prefix="quadra-wheel-") as work:
        build_dir = Path(chosen).resolve() if chosen else Path(work) / "build"
        build(build_dir)
        files = built_files(build_dir)
        return write_wheel(Path(wheel_directory), files, Path(work))


def cmake(*args):
    print("quadra_build: cmake", *args, flush=True)
    subprocess.run(["cmake", *map(str, args)], check=True)


def cache_value(cache, name):
    match = re.search(rf"^{name}:[A-Z]+=(.*)$", cache.read_text(), re.MULTILINE)
    return match.group(1) if match else ""


def build(build_dir):
    cache = build_dir / "CMakeCache.txt"
    if cache.exists():
        check_reusable(build_dir, cache)
    else:
        generator = ["-G", "Ninja"] if shutil.which("ninja") else []
        # QUADRA_WERROR stays off: a newer compiler's new warning must not
        # stop a user's install.
        cmake("-S", SOURCE, "-B", build_dir, *generator, "-DCMAKE_BUILD_TYPE=Release",
              "-DQUADRA_BUILD_TESTS=OFF", "-DQUADRA_BUILD_BENCH=OFF", "-DQUADRA_BUILD_PYTHON=ON",
              f"-DPython3_EXECUTABLE={sys.executable}")
    # cmake reads CMAKE_BUILD_PARALLEL_LEVEL itself; otherwise every core
    # (make's default is one).
    jobs = ["--parallel", os.cpu_count() or 1]
    if os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL"):
        jobs = []
    cmake("--build", build_dir, "--target", *TARGETS, *jobs)


def check_reusable(build_dir, cache):
    home = cache_value(cache, "CMAKE_HOME_DIRECTORY")
    if Path(home).resolve() != SOURCE:
        raise BuildError(f"{build_dir} is a build of {home}, not of {SOURCE}")
    if cache_value(cache, "QUADRA_SANITIZE"):
        # Its module loads only with the sanitizer's runtime preloaded.
        raise BuildError(f"{build_dir} is a sanitizer build: its module cannot be installed")
    if cache_value(cache, "QUADRA_BUILD_PYTHON").upper() in ("", "OFF", "FALSE", "0", "NO"):
        raise BuildError(f"{build_dir} was configured without the module (QUADRA_BUILD_PYTHON)")


def built_files(build_dir):
    listing = build_dir / WHEEL_FILES
    files = dict(line.split("=", 1) for line in listing.read_text().splitlines() if line)
    # A tree configured for another Python would give a module this one cannot import.
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    if not files["module"].endswith(suffix):
        raise BuildError(f"{files['module']} is not built for {sys.executable} (*{suffix}); "
                         f"{build_dir} was configured for another Python")
    return files


def wheel_tag():
    # The module is compiled against this interpreter's ABI, for this platform.
    if sys.implementation.name != "cpython":
        raise BuildError(f"the module is built for CPython only, not {sys.implementation.name}")
    python = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{python}-{python}{sys.abiflags}-{platform}"


def metadata(version):
    with open(SOURCE / "pyproject.toml", "rb") as f:
        project = tomllib.load(f)["project"]
    lines = ["Metadata-Version: 2.1", f"Name: {project['name']}", f"Version: {version}",
             f"Summary: {project['description']}",
             f"Requires-Python: {project['requires-python']}"]
    lines += [f"Requires-Dist: {requirement}" for requirement in project["dependencies"]]
    return project["name"], "\n".join(lines) + "\n"


def module_with_runpath(files, work):
    # The build tree's module finds libquadra.so by an absolute RUNPATH into
    # that tree; the wheel's finds it beside itself. CMake rewrites the entry
    # in place, as `cmake --install` does, so the new one must fit in the
    # old (CMake pads a build RUNPATH to the length of the install one).
    module = work / Path(files["module"]).name
    shutil.copyfile(files["module"], module)
    script = work / "set_runpath.cmake"
    script.write_text('file(RPATH_SET FILE "${MODULE}" NEW_RPATH "${RUNPATH}")\n')
    runpath = f"$ORIGIN/{LIBS}"
    try:
        cmake(f"-DMODULE={module}", f"-DRUNPATH={runpath}", "-P", script)
    except subprocess.CalledProcessError as error:
        raise BuildError(f"could not set the module's RUNPATH to {runpath}; a build "
                         "directory with a longer path leaves it room") from error
    return module.read_bytes()


def record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def write_wheel(wheel_directory, files, work):
    version = files["version"]
    name, meta = metadata(version)
    tag = wheel_tag()
    dist_info = f"{name}-{version}.dist-info"
    members = [
        (Path(files["module"]).name, module_with_runpath(files, work), 0o755),
        (f"{LIBS}/{files['soname']}", Path(files["library"]).read_bytes(), 0o755),
        (f"{dist_info}/METADATA", meta.encode(), 0o644),
        (f"{dist_info}/WHEEL", (f"Wheel-Version: 1.0\nGenerator: quadra_build\n"
                                f"Root-Is-Purelib: false\nTag: {tag}\n").encode(), 0o644),
    ]
    records = [record_line(member, data) for member, data, _ in members]
    records.append(f"{dist_info}/RECORD,,")
    members.append((f"{dist_info}/RECORD", ("\n".join(records) + "\n").encode(), 0o644))
    wheel_name = f"{name}-{version}-{tag}.whl"
    with zipfile.ZipFile(wheel_directory / wheel_name, "w", zipfile.ZIP_DEFLATED) as wheel:
        for member, data, mode in members:
            info = zipfile.ZipInfo(member, date_time=ZIP_TIME)
            info.external_attr = (0o100000 | mode) << 16  # a regular file and its mode
            info.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(info, data)
    print(f"quadra_build: wrote {wheel_name}", flush=True)
    return wheel_name
