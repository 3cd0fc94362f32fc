"""`pip install bindings/python` (no network, no build isolation) into a directory, then the installed package
and its `tetprobe` console script against the library found by $TETPROBE_LIBRARY, next to the package, or the
system's search path (here LD_LIBRARY_PATH)."""
import ctypes.util
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import tetprobe

BINDINGS = os.path.join(os.path.dirname(__file__), "..", "..", "bindings", "python")
LIBRARY = os.path.abspath(tetprobe.library_path)

SMOKE = """
import numpy as np, tetprobe
positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
store = tetprobe.Store.build(positions, np.arange(108, dtype=np.float32).reshape(4, 27))
sh, hint = store.interpolate([0.25, 0.25, 0.25])
print(tetprobe.__file__)
print(tetprobe.library_path)
print(float(sh[0]), hint)
"""


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The directory pip installed the package into (a copy of the sources is built, so the tree stays clean)."""
    work = tmp_path_factory.mktemp("pip")
    source = work / "source"
    shutil.copytree(BINDINGS, source, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info", "*.so"))
    target = work / "site"
    result = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--no-build-isolation", "--no-index",
                             "--no-cache-dir", "--disable-pip-version-check", "--quiet", "--target", str(target),
                             str(source)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, "pip install failed (run .ci/install-deps.sh for python3-pip, " \
                                   "python3-setuptools, python3-wheel):\n" + result.stdout + result.stderr
    return target


def environment(site, **variables):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TETPROBE_LIBRARY", "LD_LIBRARY_PATH")}
    env["PYTHONPATH"] = str(site)
    env.update(variables)
    return env


def smoke(site, **variables):
    result = subprocess.run([sys.executable, "-c", SMOKE], capture_output=True, text=True, timeout=120,
                            env=environment(site, **variables), cwd=str(site))
    return result


def test_installed_package_builds_and_queries_through_tetprobe_library(installed):
    result = smoke(installed, TETPROBE_LIBRARY=LIBRARY)
    assert result.returncode == 0, result.stderr
    package_file, library, answer = result.stdout.splitlines()
    assert package_file == str(installed / "tetprobe" / "__init__.py")
    assert library == LIBRARY
    # The centroid of the tetrahedron weighs each probe 1/4: SH coefficient 0 is the mean of 0, 27, 54, 81.
    assert answer == "40.5 0"
    metadata = next(installed.glob("tetprobe-*.dist-info"))
    assert metadata.name == "tetprobe-%s.dist-info" % tetprobe.__version__


def test_console_script_is_the_command(installed):
    script = installed / "bin" / "tetprobe"
    assert script.exists()
    result = subprocess.run([str(script), "version"], capture_output=True, text=True, timeout=120,
                            env=environment(installed, TETPROBE_LIBRARY=LIBRARY))
    assert result.returncode == 0, result.stderr
    assert result.stdout == "tetprobe %d.%d.%d\n" % tetprobe.library_version()
    result = subprocess.run([str(script), "frobnicate"], capture_output=True, text=True, timeout=120,
                            env=environment(installed, TETPROBE_LIBRARY=LIBRARY))
    assert result.returncode == 2 and result.stderr.startswith('tetprobe: unknown command "frobnicate"\nusage:')


def install_like_the_system(library, directory):
    """Copies library into directory as an install would: the real file (libtetprobe.so.X.Y.Z) and a link
    for each shorter name (libtetprobe.so, .so.X, .so.X.Y), so whichever name find_library reports (the
    SONAME) resolves."""
    real = pathlib.Path(os.path.realpath(library))
    shutil.copy(real, directory / real.name)
    stem, _, version = real.name.partition(".so")
    parts = [part for part in version.split(".") if part]
    for count in range(len(parts)):
        name = stem + ".so" + "".join("." + part for part in parts[:count])
        (directory / name).symlink_to(real.name)


def test_library_next_to_the_package_and_on_the_system_path(installed, tmp_path):
    # On the system's search path: LD_LIBRARY_PATH is what ctypes.util.find_library consults for users' libs.
    system_dir = tmp_path / "lib"
    system_dir.mkdir()
    install_like_the_system(LIBRARY, system_dir)
    result = smoke(installed, LD_LIBRARY_PATH=str(system_dir))
    assert result.returncode == 0, result.stderr
    assert "libtetprobe.so" in result.stdout.splitlines()[1]  # the name found (the SONAME where it has one)
    # Next to the package: found before the system's.
    beside = installed / "tetprobe" / "libtetprobe.so"
    shutil.copy(LIBRARY, beside)
    try:
        result = smoke(installed, LD_LIBRARY_PATH=str(system_dir))
        assert result.returncode == 0, result.stderr
        assert result.stdout.splitlines()[1] == str(beside)
    finally:
        beside.unlink()
    # Nowhere: a clear ImportError (unless this machine has a libtetprobe installed system-wide).
    if ctypes.util.find_library("tetprobe") is None:
        result = smoke(installed)
        assert result.returncode != 0
        assert "ImportError: libtetprobe not found; set TETPROBE_LIBRARY" in result.stderr
    result = smoke(installed, TETPROBE_LIBRARY=str(tmp_path / "missing.so"))
    assert "ImportError: TETPROBE_LIBRARY=%s cannot be loaded" % (tmp_path / "missing.so") in result.stderr
