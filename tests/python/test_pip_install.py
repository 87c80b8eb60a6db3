"""`pip install` of the source tree into a fresh virtual environment (issue
45, pyproject.toml and python/quadra_build.py), run by CTest
(tests/CMakeLists.txt, test `PipInstall`) as

    test_pip_install.py PYTHON SOURCE_DIR BUILD_DIR GLB VERSION

The venv is PYTHON's, with its system site-packages (numpy). pip gets no
index and installs with build isolation, as a user's `pip install .` does;
it reuses BUILD_DIR (config setting build-dir), so what this test adds to
the suite is the packing and the install, not a second build. Then the
installed module must be the one imported, say VERSION, and render GLB as
the build tree's module does, bit for bit; `pip uninstall` must remove all
it installed (the wheel's RECORD), and the source tree must be as it was.
"""
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

PYTHON, SOURCE, BUILD, GLB, VERSION = sys.argv[1:6]

# Run by each module: where it was imported from, its version, and a frame.
RENDER = """
import sys
import numpy as np
import quadra
print(quadra.__file__)
print(quadra.__version__)
out = quadra.Renderer(threads=2).render(quadra.load(sys.argv[1]), width=64, height=48)
np.save(sys.argv[2], out.color)
"""

# No PYTHONPATH (the build tree's module must not be the one found), no
# network, no wheel cache in the home folder, no bytecode in the source tree.
ENV = {name: value for name, value in os.environ.items()
       if name != "PYTHONPATH" and not name.startswith("PIP_")}
ENV.update(PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_CACHE_DIR="1",
           PIP_NO_INPUT="1", PYTHONDONTWRITEBYTECODE="1")


def run(args, **options):
    shown = ("<script>" if "\n" in str(arg) else str(arg) for arg in args)
    print("+", *shown, flush=True)
    return subprocess.run(list(map(str, args)), env=options.pop("env", ENV), check=True,
                          **options)


def check(condition, message):
    if not condition:
        sys.exit(f"test_pip_install: {message}")


def source_state():
    # Every untracked or ignored path, apart from the build tree: what a
    # build that writes into the source tree would change.
    listing = subprocess.run(["git", "-C", SOURCE, "status", "--porcelain", "--ignored"],
                             capture_output=True, text=True)
    if listing.returncode != 0:
        return None  # not a git checkout: nothing to compare
    build = os.path.relpath(BUILD, SOURCE)
    return sorted(line for line in listing.stdout.splitlines()
                  if line[3:].rstrip("/") != build)


def render(python, work, name, env=ENV):
    frame = Path(work) / f"{name}.npy"
    printed = run([python, "-c", RENDER, GLB, frame], env=env, cwd=work, capture_output=True,
                  text=True).stdout.split()
    return Path(printed[0]).resolve(), printed[1], np.load(frame)


def main():
    before = source_state()
    with tempfile.TemporaryDirectory(prefix="quadra-pip-") as work:
        venv = Path(work) / "venv"
        run([PYTHON, "-m", "venv", "--system-site-packages", venv])
        python = venv / "bin" / "python"
        run([python, "-m", "pip", "install", "--no-deps", "--config-settings",
             f"build-dir={BUILD}", SOURCE])

        where, version, color = render(python, work, "installed")
        check(venv.resolve() in where.parents, f"quadra imported from {where}, not from {venv}")
        check(version == VERSION, f"quadra.__version__ is {version}, the library's is {VERSION}")
        check(np.isfinite(color).all(), "the frame has values that are not finite")
        covered = int((color[..., 3] > 0).sum())
        check(covered > color.shape[0] * color.shape[1] // 8, f"only {covered} pixels covered")

        in_tree = dict(ENV, PYTHONPATH=str(Path(BUILD) / "python"))
        where, _, reference = render(PYTHON, work, "build_tree", env=in_tree)
        check(Path(BUILD).resolve() in where.parents, f"the build tree's quadra is {where}")
        check(np.array_equal(color.view(np.uint32), reference.view(np.uint32)),
              "the installed module's frame differs from the build tree's")

        site = Path(run([python, "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"],
                        capture_output=True, text=True).stdout.strip())
        run([python, "-m", "pip", "uninstall", "--yes", "quadra"])
        left = sorted(path.name for path in site.glob("quadra*"))
        check(not left, f"pip uninstall left {left} in {site}")
    check(source_state() == before, "pip install changed the source tree (git status --ignored)")
    print("test_pip_install: installed, rendered the build tree's frame, uninstalled")


if __name__ == "__main__":
    main()
