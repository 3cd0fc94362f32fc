"""The README's "Using it" snippets, built and run exactly as printed: the fenced blocks are read from README.md.

- C: each ```c block is a whole program, written to the file its first comment names; the ```sh block installs
  the build tree (`build`, a link to $TETPROBE_BUILD_DIR here) and builds and runs both programs with their
  pkg-config lines. The one change: the prefix /opt/tetprobe becomes a folder of this test's.
- Python: the ```python block runs as a script from a folder where samples/ is the repository's.
- C#: the ```csharp block is the body of a Main (the only thing around it), compiled with the binding by mcs and run
  by mono.
The results are checked against what the stores they write answer."""
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import tetprobe

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
README = os.path.join(ROOT, "README.md")


def using_it_blocks(language):
    """The fenced blocks of `language` in the README's "Using it" section, in order."""
    with open(README, encoding="utf-8") as f:
        text = f.read()
    section = text[text.index("\n## Using it\n"):]
    section = section[:section.index("\n## ", 1)]
    return re.findall(r"\n```%s\n(.*?)\n```\n" % re.escape(language), section, re.S)


def build_directory():
    folder = os.environ.get("TETPROBE_BUILD_DIR") or os.path.dirname(os.path.abspath(tetprobe.library_path))
    if not os.path.exists(os.path.join(folder, "CMakeCache.txt")):
        pytest.skip("no CMake build tree for the library (set TETPROBE_BUILD_DIR)")
    return folder


def clean_environment(**variables):
    env = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "PKG_CONFIG_PATH")}
    env.update(variables)
    return env


def test_the_c_programs_build_and_run_with_their_pkg_config_lines(tmp_path):
    programs = using_it_blocks("c")
    shell = using_it_blocks("sh")
    assert len(programs) == 2 and len(shell) == 1
    for program in programs:
        name = re.match(r"/\* (\w+\.c): ", program).group(1)
        (tmp_path / name).write_text(program + "\n")
    (tmp_path / "build").symlink_to(build_directory())
    script = shell[0].replace("/opt/tetprobe", str(tmp_path / "prefix"))
    assert script.count(str(tmp_path / "prefix")) == 2
    result = subprocess.run(["bash", "-euo", "pipefail", "-c", script], cwd=str(tmp_path), capture_output=True,
                            text=True, timeout=600, env=clean_environment())
    assert result.returncode == 0, result.stdout + result.stderr
    # The centre (1, 1, 1) of the probes' tetrahedron weighs the 4 probes 1/4 each: red L00 = (1+2+3+4)/4; the
    # irradiance of an ambient L00 is pi * L00 * Y00 (the header's SH contract).
    line = [l for l in result.stdout.splitlines() if l.startswith("irradiance from above: ")]
    assert len(line) == 1, result.stdout
    rgb = [float(v) for v in line[0].split(":")[1].split()]
    assert rgb == pytest.approx([np.pi * 0.282095 * 2.5, 0, 0], abs=2e-4)
    assert Store_probes(tmp_path / "level.tpb") == 4
    # game links the run-time library only, found through the RPATH (no LD_LIBRARY_PATH here).
    linked = subprocess.run(["ldd", str(tmp_path / "game")], capture_output=True, text=True, env=clean_environment())
    assert "libtetprobe_runtime.so" in linked.stdout and "libtetprobe.so" not in linked.stdout
    assert str(tmp_path / "prefix") in linked.stdout


def Store_probes(path):
    return tetprobe.Store.load(str(path)).info()["probes"]


def with_samples(folder):
    """folder/samples is the repository's samples/ (the snippets open samples/scenes/two_rooms.json)."""
    (folder / "samples").symlink_to(os.path.join(ROOT, "samples"))


def test_the_python_snippet_runs(tmp_path):
    snippet, = using_it_blocks("python")
    with_samples(tmp_path)
    (tmp_path / "snippet.py").write_text(snippet + "\n")
    package = os.path.dirname(os.path.dirname(os.path.abspath(tetprobe.__file__)))
    result = subprocess.run([sys.executable, "snippet.py"], cwd=str(tmp_path), capture_output=True, text=True,
                            timeout=600, env=dict(os.environ, PYTHONPATH=package,
                                                  TETPROBE_LIBRARY=os.path.abspath(tetprobe.library_path)))
    assert result.returncode == 0, result.stderr
    printed = np.array([[float(v) for v in row.split()] for row in re.findall(r"\[([^\[\]]+)\]", result.stdout)])
    store = tetprobe.Store.load(str(tmp_path / "level.tpb"))
    assert store.info()["leak_edges"] > 0
    points = np.array([[2.0, 1.2, 2.0], [6.0, 1.2, 2.0]], np.float32)
    expected = tetprobe.sh.eval_irradiance(store.interpolate(points)[0], (0, 1, 0))
    assert printed.shape == (2, 3) and (expected > 0).all()
    np.testing.assert_allclose(printed, expected, rtol=1e-6)


WRAPPER = """using System;
using TetProbe;

static class ReadmeSnippet
{
    static void Main()
    {
%s
    }
}
"""


def test_the_csharp_snippet_compiles_and_runs(tmp_path):
    snippet, = using_it_blocks("csharp")
    for tool in ("mcs", "mono"):
        assert shutil.which(tool), "%s not found: run .ci/install-deps.sh (mono-mcs, mono-runtime)" % tool
    with_samples(tmp_path)
    (tmp_path / "Readme.cs").write_text(WRAPPER % snippet)
    binding = os.path.join(ROOT, "bindings", "csharp")
    sources = sorted(os.path.join(binding, name) for name in os.listdir(binding) if name.endswith(".cs"))
    compiled = subprocess.run(["mcs", "-nologo", "-warnaserror", "-target:exe", "-out:" + str(tmp_path / "Readme.exe"),
                               str(tmp_path / "Readme.cs")] + sources, capture_output=True, text=True, timeout=600)
    assert compiled.returncode == 0, compiled.stdout + compiled.stderr
    (tmp_path / "libtetprobe.so").symlink_to(os.path.abspath(tetprobe.library_path))
    result = subprocess.run(["mono", str(tmp_path / "Readme.exe")], cwd=str(tmp_path), capture_output=True, text=True,
                            timeout=600, env=dict(os.environ, LD_LIBRARY_PATH=str(tmp_path)))
    assert result.returncode == 0, result.stdout + result.stderr
    store = tetprobe.Store.load(str(tmp_path / "level.tpb"))
    assert store.info()["compact"] and store.info()["leak_edges"] > 0
    expected = tetprobe.sh.eval_irradiance(store.interpolate([2.0, 1.2, 2.0])[0], (0, 1, 0))
    printed = [float(v) for v in re.fullmatch(r"\((.*)\)\n", result.stdout).group(1).split(",")]
    np.testing.assert_allclose(printed, expected, rtol=1e-5)
