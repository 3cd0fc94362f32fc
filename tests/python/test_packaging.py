"""`pip install bindings/python` (no network, no build isolation, the in-tree build backend) into a directory and
into a plain venv, then the installed package against the library found by $TETPROBE_LIBRARY, next to the package,
or the system's search path (here LD_LIBRARY_PATH), and `python -m tetprobe` running the tool `cmake --install`
put beside the installed library."""
import base64
import ctypes.util
import hashlib
import os
import pathlib
import shutil
import subprocess
import sys
import zipfile

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
    assert result.returncode == 0, "pip install failed (run .ci/install-deps.sh for python3-pip):\n" + \
        result.stdout + result.stderr
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


def build_directory():
    """The CMake build tree of the library under test: $TETPROBE_BUILD_DIR, or the library's own folder."""
    folder = os.environ.get("TETPROBE_BUILD_DIR") or os.path.dirname(LIBRARY)
    if not os.path.exists(os.path.join(folder, "CMakeCache.txt")):
        pytest.skip("no CMake build tree for the library (set TETPROBE_BUILD_DIR)")
    return folder


def test_python_m_tetprobe_runs_the_installed_tool_beside_the_installed_library(installed, tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build_directory(), "--prefix", str(prefix)], check=True, capture_output=True,
                   timeout=300)
    tool = prefix / "bin" / "tetprobe"
    libraries = list(prefix.glob("lib*/**/libtetprobe.so"))
    assert tool.exists() and len(libraries) == 1
    assert not (installed / "bin").exists()  # no console script: one command line, the C tool
    env = environment(installed, TETPROBE_LIBRARY=str(libraries[0].parent), PATH="/usr/bin:/bin")
    result = subprocess.run([sys.executable, "-m", "tetprobe", "version"], capture_output=True, text=True, timeout=120,
                            env=env)
    # The installed tool runs without LD_LIBRARY_PATH (its RPATH names the installed library).
    assert result.returncode == 0, result.stderr
    assert result.stdout == "tetprobe %d.%d.%d\n" % tetprobe.library_version()
    result = subprocess.run([sys.executable, "-m", "tetprobe", "frobnicate"], capture_output=True, text=True,
                            timeout=120, env=env)
    assert result.returncode == 2 and result.stderr.startswith('tetprobe: unknown command "frobnicate"\nusage:')


def test_pip_installs_into_a_plain_venv_without_network(tmp_path):
    """The README's command in a venv made by Debian's python3 -m venv: pip there has no wheel package (so no
    bdist_wheel), and --no-build-isolation with the in-tree backend needs none. A venv with the system's site
    packages (numpy from python3-numpy) then imports and queries it."""
    source = tmp_path / "source"
    shutil.copytree(BINDINGS, source, ignore=shutil.ignore_patterns("__pycache__", "*.so"))
    for name, flags in (("plain", []), ("system", ["--system-site-packages"])):
        venv = tmp_path / name
        subprocess.run(["/usr/bin/python3", "-m", "venv", *flags, str(venv)], check=True, capture_output=True,
                       timeout=300)
        python = venv / "bin" / "python"
        if name == "plain":  # what made setuptools' bdist_wheel fail here
            assert subprocess.run([str(python), "-c", "import wheel"], capture_output=True).returncode != 0
        result = subprocess.run([str(venv / "bin" / "pip"), "install", "--no-deps", "--no-build-isolation", "--no-index",
                                 "--disable-pip-version-check", str(source)], capture_output=True, text=True,
                                timeout=300)
        assert result.returncode == 0, result.stdout + result.stderr
        listed = subprocess.run([str(python), "-m", "pip", "show", "-f", "tetprobe"], capture_output=True, text=True,
                                timeout=120).stdout
        assert "Version: %s" % tetprobe.__version__ in listed
        assert {"tetprobe/__init__.py", "tetprobe/tool.py", "tetprobe/__main__.py"} <= \
            {line.strip() for line in listed.splitlines()}
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "TETPROBE_LIBRARY")}
    env["TETPROBE_LIBRARY"] = LIBRARY
    result = subprocess.run([str(tmp_path / "system" / "bin" / "python"), "-c", SMOKE], capture_output=True, text=True,
                            timeout=120, env=env, cwd=str(tmp_path))
    assert result.returncode == 0, result.stderr
    package_file, library, answer = result.stdout.splitlines()
    assert package_file.startswith(str(tmp_path / "system" / "lib")) and answer == "40.5 0"
    assert not list(source.glob("*.egg-info")) and not (source / "build").exists()  # the source tree stays clean


def test_the_wheel_is_reproducible_and_records_every_file(tmp_path):
    sys.path.insert(0, os.path.join(BINDINGS, "backend"))
    try:
        import tetprobe_backend
    finally:
        sys.path.pop(0)
    names = []
    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
        names.append(tetprobe_backend.build_wheel(str(tmp_path / folder)))
    assert names[0] == names[1] == "tetprobe-%s-py3-none-any.whl" % tetprobe.__version__
    assert (tmp_path / "a" / names[0]).read_bytes() == (tmp_path / "b" / names[1]).read_bytes()
    with zipfile.ZipFile(tmp_path / "a" / names[0]) as wheel:
        record = wheel.read("tetprobe-%s.dist-info/RECORD" % tetprobe.__version__).decode().splitlines()
        members = set(wheel.namelist())
        for line in record:
            name, digest, size = line.rsplit(",", 2)
            assert name in members
            if digest:
                data = wheel.read(name)
                assert digest == "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
                assert int(size) == len(data)
    assert {line.rsplit(",", 2)[0] for line in record} == members
    assert "tetprobe/cli.py" not in members and "tetprobe/tool.py" in members


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
