"""`python3 -m tetprobe` is the C tool ($TETPROBE_CLI): the same arguments give the same output, files and exit
status, because it runs that tool. Also where the tool is looked for, and the message when it is nowhere."""
import os
import shutil
import stat
import subprocess
import sys

import numpy as np
import pytest

import tetprobe
from tetprobe import tool

C_TOOL = os.environ.get("TETPROBE_CLI", "")
needs_c_tool = pytest.mark.skipif(not (C_TOOL and os.path.exists(C_TOOL)), reason="TETPROBE_CLI is not set")
SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")


def environment(**variables):
    env = {k: v for k, v in os.environ.items() if k != "TETPROBE_TOOL"}
    env.update(variables)
    return env


def run(command, args, stdin=None, **variables):
    """(status, stdout bytes, stderr bytes) of command + args."""
    result = subprocess.run(command + [str(a) for a in args], input=stdin, capture_output=True, timeout=300,
                            env=environment(**variables))
    return result.returncode, result.stdout, result.stderr


def python_m(args, stdin=None, **variables):
    return run([sys.executable, "-m", "tetprobe"], args, stdin, **variables)


def probe_csv(path, n=40, seed=5):
    rng = np.random.default_rng(seed)
    positions = (rng.random((n, 3)) * 4).astype(np.float32)
    sh = rng.uniform(-1, 1, (n, 27)).astype(np.float32)
    lines = ["x,y,z," + ",".join("sh%d" % k for k in range(27))]
    lines += [", ".join("%.9g" % v for v in np.concatenate([p, s])) for p, s in zip(positions, sh)]
    path.write_text("\n".join(lines) + "\n")
    return positions


@needs_c_tool
def test_python_m_tetprobe_gives_the_c_tools_output_files_and_status(tmp_path):
    positions = probe_csv(tmp_path / "probes.csv")
    garbage = tmp_path / "garbage.tpb"
    garbage.write_bytes(b"\x00" * 300)
    store = tmp_path / "store.tpb"
    subprocess.run([C_TOOL, "build", str(tmp_path / "probes.csv"), "-o", str(store)], check=True, capture_output=True)
    point = ["%.9g" % v for v in positions[:4].mean(axis=0)]
    scene = os.path.join(SCENES, "cornell_box.json")
    cases = [["version"], ["info", store], ["info", store, "--json"], ["query", store, *point, "--weights", "--json"],
             ["query", store, "-50", "2", "2"], ["plan", scene, "--json"], ["info", tmp_path / "missing.tpb"],
             ["query", garbage, 0, 0, 0], ["query", garbage, "x", 0, 0], ["frobnicate"], [], ["--help"]]
    statuses = set()
    for args in cases:
        c = run([C_TOOL], args)
        python = python_m(args)
        assert python == c, args
        statuses.add(c[0])
    assert statuses == {0, 1, 2}  # success, a failure and a usage error all come through
    # Files: the same bytes written where the arguments say.
    for command, out in (([C_TOOL], tmp_path / "c.tpb"), ([sys.executable, "-m", "tetprobe"], tmp_path / "py.tpb")):
        status, stdout, _ = run(command, ["build", tmp_path / "probes.csv", "-o", out, "--compact"])
        assert status == 0 and b"40 probes" in stdout
    assert (tmp_path / "c.tpb").read_bytes() == (tmp_path / "py.tpb").read_bytes()


def fake_tool(folder, name="tetprobe"):
    """A stand-in tool that echoes its arguments, copies stdin to stdout and exits with status 7."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text("#!/bin/sh\necho \"args:$*\"\ncat\necho oops >&2\nexit 7\n")
    path.chmod(path.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return path


def test_arguments_stdin_stdout_stderr_and_status_pass_through(tmp_path, monkeypatch, capfd):
    fake = fake_tool(tmp_path / "bin")
    status, out, err = python_m(["query", "a b", "--json"], stdin=b"from stdin\n", TETPROBE_TOOL=str(fake))
    assert (status, out, err) == (7, b"args:query a b --json\nfrom stdin\n", b"oops\n")
    # TETPROBE_TOOL may name the folder holding the tool.
    assert python_m(["x"], TETPROBE_TOOL=str(tmp_path / "bin"))[:2] == (7, b"args:x\n")
    # In a Python program, tool.main(args) runs the tool as a child and returns its status.
    monkeypatch.setenv("TETPROBE_TOOL", str(fake))
    assert tool.main(["in", "process"]) == 7
    out, err = capfd.readouterr()
    assert out == "args:in process\n" and err == "oops\n"


def test_a_missing_tool_is_a_clear_message(tmp_path):
    status, out, err = python_m(["version"], TETPROBE_TOOL=str(tmp_path / "nothing-here"))
    assert status == tool.NOT_FOUND and out == b""
    assert err == ("tetprobe: TETPROBE_TOOL=%s is not an executable tetprobe tool\n" % (tmp_path / "nothing-here")).encode()
    # Nowhere at all: a package and library copied where no tool lies beside them, and an empty PATH.
    site = tmp_path / "site"
    shutil.copytree(os.path.dirname(tetprobe.__file__), site / "tetprobe", ignore=shutil.ignore_patterns("__pycache__"))
    library = tmp_path / "lib" / "libtetprobe.so"
    library.parent.mkdir()
    shutil.copy(tetprobe.library_path, library)
    env = environment(PYTHONPATH=str(site), TETPROBE_LIBRARY=str(library), PATH="/nonexistent")
    result = subprocess.run([sys.executable, "-m", "tetprobe", "version"], capture_output=True, text=True, timeout=60,
                            env=env)
    assert result.returncode == tool.NOT_FOUND and result.stdout == ""
    assert result.stderr.startswith("tetprobe: the tetprobe command-line tool was not found (looked in: %s, "
                                    % (tmp_path / "lib" / "tetprobe"))
    assert "set TETPROBE_TOOL" in result.stderr and "cmake --install" in result.stderr


def test_the_tool_is_found_beside_the_library_then_on_the_path(tmp_path):
    site = tmp_path / "site"
    shutil.copytree(os.path.dirname(tetprobe.__file__), site / "tetprobe", ignore=shutil.ignore_patterns("__pycache__"))
    prefix = tmp_path / "prefix"
    library = prefix / "lib" / "libtetprobe.so"
    library.parent.mkdir(parents=True)
    shutil.copy(tetprobe.library_path, library)
    on_path = fake_tool(tmp_path / "path-bin")
    env = dict(PYTHONPATH=str(site), TETPROBE_LIBRARY=str(prefix / "lib"), PATH=str(tmp_path / "path-bin"))
    assert python_m(["a"], **env)[:2] == (7, b"args:a\n")  # only on the PATH
    beside = fake_tool(prefix / "bin")  # an installed prefix: lib/ and bin/
    beside.write_text(beside.read_text().replace("args:", "prefix:"))
    assert python_m(["b"], **env)[:2] == (7, b"prefix:b\n")
    build_tree = fake_tool(prefix / "lib" / "samples")  # a build tree: the library, and the tool in samples/
    build_tree.write_text(build_tree.read_text().replace("args:", "build:"))
    assert python_m(["c"], **env)[:2] == (7, b"build:c\n")
    assert python_m(["d"], TETPROBE_TOOL=str(on_path), **env)[:2] == (7, b"args:d\n")  # the variable comes first


def test_tool_candidates_follow_the_loaded_library(monkeypatch):
    folder = os.path.dirname(os.path.abspath(tetprobe.library_path))
    candidates = tool.tool_candidates()
    assert candidates[:2] == [os.path.join(folder, "tetprobe"), os.path.join(folder, "samples", "tetprobe")]
    assert os.path.normpath(os.path.join(folder, "..", "bin", "tetprobe")) in candidates


@needs_c_tool
def test_the_library_of_a_build_tree_finds_that_build_s_tool(monkeypatch):
    monkeypatch.delenv("TETPROBE_TOOL", raising=False)
    if not os.path.samefile(os.path.dirname(os.path.dirname(C_TOOL)), os.path.dirname(tetprobe.library_path)):
        pytest.skip("TETPROBE_CLI and TETPROBE_LIBRARY come from different build trees")
    assert os.path.samefile(tool.find_tool(), C_TOOL)
