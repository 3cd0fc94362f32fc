"""`python3 -m tetprobe` against the C tool ($TETPROBE_CLI): the same inputs give the same output and files."""
import contextlib
import ctypes
import io
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import tetprobe
from tetprobe import cli

C_TOOL = os.environ.get("TETPROBE_CLI", "")
needs_c_tool = pytest.mark.skipif(not (C_TOOL and os.path.exists(C_TOOL)), reason="TETPROBE_CLI is not set")
SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")


def run(command, args):
    """(status, stdout, stderr) of a command line; None runs the Python tool in this process (quicker than a
    new interpreter per call; test_python_m_tetprobe_runs_the_same_main runs it as a program)."""
    args = [str(a) for a in args]
    if command is None:
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = cli.main(args)
        return status, out.getvalue(), err.getvalue()
    result = subprocess.run(command + args, capture_output=True, text=True, timeout=300)
    return result.returncode, result.stdout, result.stderr


def both(tmp_path, *args, files=()):
    """Runs the C tool and the Python one with args; returns their (status, stdout, stderr) and, for each
    path in files, the bytes each wrote there (read and removed after each run)."""
    results = []
    for command in ([C_TOOL], None):
        for path in files:
            if os.path.exists(path):
                os.remove(path)
        status, out, err = run(command, args)
        written = [open(path, "rb").read() if os.path.exists(path) else None for path in files]
        results.append((status, out, err, written))
    return results


def assert_same(c, python):
    assert c[0] == python[0], (c, python)
    assert c[1] == python[1]
    assert c[2] == python[2]
    assert c[3] == python[3]


def probe_csv(path, n=40, seed=5, header=True):
    rng = np.random.default_rng(seed)
    positions = (rng.random((n, 3)) * 4).astype(np.float32)
    sh = rng.uniform(-1, 1, (n, 27)).astype(np.float32)
    lines = ["x,y,z," + ",".join("sh%d" % k for k in range(27))] if header else []
    lines += ["# a comment", ""]
    lines += [", ".join("%.9g" % v for v in np.concatenate([p, s])) for p, s in zip(positions, sh)]
    path.write_text("\n".join(lines) + "\n")
    return positions


@needs_c_tool
def test_build_info_and_query_match_the_c_tool(tmp_path):
    positions = probe_csv(tmp_path / "probes.csv")
    store = tmp_path / "store.tpb"
    for extra in ([], ["--compact"]):
        c, python = both(tmp_path, "build", tmp_path / "probes.csv", "-o", store, *extra, files=[store])
        assert c[0] == 0 and c[3][0] is not None
        assert_same(c, python)
    run([C_TOOL], ["build", tmp_path / "probes.csv", "-o", store])
    for flags in ([], ["--json"]):
        assert_same(*both(tmp_path, "info", store, *flags))
    inside = positions[:4].mean(axis=0)
    points = [inside, positions[7], [-50.0, 2.0, 2.0], [1e9, -3.0, 0.5]]
    for point in points:
        coordinates = ["%.9g" % v for v in point]
        for flags in ([], ["--weights"], ["--json"], ["--weights", "--json"]):
            c, python = both(tmp_path, "query", store, *coordinates, *flags)
            assert c[0] == 0
            assert_same(c, python)


@needs_c_tool
def test_json_probe_files_and_their_errors_match(tmp_path):
    store = tmp_path / "store.tpb"
    good = tmp_path / "probes.json"
    good.write_text('{"probes": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.1, 0.2, 0.3], [16777217, 0.5, 3e-39]]}')
    assert_same(*both(tmp_path, "build", good, "-o", store, files=[store]))
    cases = {
        "no_probes.json": '{"probe": []}',
        "not_xyz.json": '{"probes": [[0, 0], [1, 1, 1]]}',
        "bool.json": '{"probes": [[0, 0, true]]}',
        "sh_count.json": '{"probes": [[0, 0, 0]], "sh": []}',
        "sh_width.json": '{"probes": [[0, 0, 0]], "sh": [[1, 2]]}',
        "sh_text.json": '{"probes": [[0, 0, 0]], "sh": [[' + ", ".join(["1"] * 26) + ', "x"]]}',
        "empty.json": '{"probes": []}',
        "nan.json": '{"probes": [[0, 0, 0], [1e39, 0, 0]]}',
    }
    for name, text in cases.items():
        (tmp_path / name).write_text(text)
        c, python = both(tmp_path, "build", tmp_path / name, "-o", store, files=[store])
        assert c[0] == 1 and c[3] == [None], name
        assert_same(c, python)
    (tmp_path / "broken.json").write_text('{"probes": [[0, 0, 0]')
    c, python = both(tmp_path, "build", tmp_path / "broken.json", "-o", store, files=[store])
    assert c[0] == python[0] == 1 and c[3] == python[3] == [None]
    assert "broken.json: invalid JSON: " in c[2] and "broken.json: invalid JSON: " in python[2]


@needs_c_tool
def test_csv_numbers_are_read_as_strtof_reads_them(tmp_path):
    # 1 + 2^-24 + a little rounds to 1 + 2^-23 as a float; through a double first it would tie back to 1.
    tricky = ["1.0000000596046447753906250001", "0x1.8p1", "1e-40", "-0", ".5", "5.", "+2.5E+1", "\v7"]
    lines = ["%s,%d,%d" % (value, k % 3, k // 3) for k, value in enumerate(tricky)]
    lines += ["0,0,2,", " 1 , 2 , 2 "]
    (tmp_path / "tricky.csv").write_text("\n".join(lines) + "\n")
    store = tmp_path / "store.tpb"
    c, python = both(tmp_path, "build", tmp_path / "tricky.csv", "-o", store, files=[store])
    assert c[0] == 0
    assert_same(c, python)
    libc = ctypes.CDLL(None)
    libc.strtof.restype = ctypes.c_float
    libc.strtof.argtypes = (ctypes.c_char_p, ctypes.c_void_p)
    for text in tricky + ["3.4028235e38", "3.40282357e38", "1e-46", "0x1.fffffffp0", "inf", "-Infinity", "1e500"]:
        ours = cli.parse_float32(text)
        reference = np.float32(libc.strtof(text.encode(), None))
        assert ours.tobytes() == reference.tobytes(), text
    assert cli.parse_float32(tricky[0]) == np.float32(1) + np.float32(2.0 ** -23)
    for rejected in ["", "1,5", "1 2", "0x", "1e", "nanx", "1_0", "--1"]:
        assert cli.parse_float32(rejected) is None, rejected
    bad = {"short.csv": "0,0,0\n1,2\n", "text.csv": "0,0,0\n1,x,0\n",
           "mixed.csv": "0,0,0\n" + ",".join(["1"] * 30) + "\n",
           "double_comma.csv": "0,0,0,,\n", "overflow.csv": "0,0,0\n3.5e38,0,0\n", "nan.csv": "0,0,0\n1,nan,0\n",
           "probes.dat": "0,0,0\n", "empty.csv": "x,y,z\n"}
    for name, text in bad.items():
        (tmp_path / name).write_text(text)
        c, python = both(tmp_path, "build", tmp_path / name, "-o", store, files=[store])
        assert c[0] == 1 and c[3] == [None], name
        assert_same(c, python)


@needs_c_tool
@pytest.mark.parametrize("name", ["cornell_box.json", "two_rooms.json"])
def test_plan_matches_the_c_tool(tmp_path, name):
    scene = os.path.join(SCENES, name)
    for flags in ([], ["--json"], ["--bounces", "0", "--json"]):
        c, python = both(tmp_path, "plan", scene, *flags)
        assert c[0] == 0 and ("effects plan: direct: " in c[1] or '"direct_lights": ' in c[1])
        assert_same(c, python)
        if "--json" in flags:  # the count of probes inside geometry, as find_inside_probes finds them
            scene_object = tetprobe.Scene.load(scene)
            inside = len(tetprobe.find_inside_probes(scene_object, scene_object.probes))
            assert '\n  "inside_probes": %d,\n  "text": ' % inside in c[1]


@needs_c_tool
def test_bake_matches_the_c_tool_byte_for_byte(tmp_path):
    scene = os.path.join(SCENES, "cornell_box.json")
    store = tmp_path / "cornell.tpb"
    c, python = both(tmp_path, "bake", scene, "-o", store, "--rays", "16", "--bounces", "1", "--seed", "3",
                     "--threads", "1", files=[store])
    assert c[0] == 0 and c[3][0] is not None and "100%" in c[2]
    timing = re.compile(r" in \d+\.\d\d s \(\d+ probe-rays/s\)")
    assert timing.search(c[1]) and timing.search(python[1])
    assert timing.sub("", c[1]) == timing.sub("", python[1])
    assert (c[0], c[3]) == (python[0], python[3])  # the store's bytes
    # Progress lines: how many come depends on timing (a slow bake reports more), their form does not.
    for err in (c[2], python[2]):
        assert err.endswith("bake   100% bake\n")
        assert all(re.fullmatch(r"bake   [ \d]{2}\d% bake", line) for line in err.splitlines())


@needs_c_tool
def test_plan_json_counts_the_probes_inside_geometry(tmp_path):
    # The two rooms plus a probe inside the table (a closed box from x 5.6 to 6.8, y 0 to 0.75, z 1.4 to 2.6).
    with open(os.path.join(SCENES, "two_rooms.json")) as f:
        document = json.load(f)
    shutil.copy(os.path.join(SCENES, document["meshes"][0]["obj"]), tmp_path)
    document["probes"].append([6.2, 0.4, 2.0])
    scene = tmp_path / "inside.json"
    scene.write_text(json.dumps(document))
    c, python = both(tmp_path, "plan", scene, "--json")
    assert c[0] == 0
    assert_same(c, python)
    last = len(document["probes"]) - 1
    assert '\n  "inside_probes": 1,\n' in c[1] and "inside geometry: 1 probe (%d)" % last in c[1]


def assert_progress_lines(err, label):
    """Progress lines on stderr: how many come depends on timing, their form does not."""
    lines = [line for line in err.splitlines() if "%" in line]
    assert lines and all(re.fullmatch(label + r" +[ \d]{2}\d% [a-z]+", line) for line in lines), err
    return [line for line in err.splitlines() if "%" not in line]


@needs_c_tool
@pytest.mark.parametrize("mode", ["whole", "walkable"])
def test_place_matches_the_c_tool_byte_for_byte(tmp_path, mode):
    scene = os.path.join(SCENES, "two_rooms.json")
    probes, curve = tmp_path / "probes.csv", tmp_path / "curve.json"
    c, python = both(tmp_path, "place", scene, "-o", probes, "--curve", curve, "--mode", mode, "--spacing", "1",
                     "--target", "40", "--rays", "32", "--seed", "7", "--threads", "1", files=[probes, curve])
    assert c[0] == python[0] == 0, (c, python)
    assert c[3][0] == python[3][0]  # the CSV's bytes
    assert c[3][0].count(b"\n") == 40 and re.fullmatch(rb"([-\d.e+]+,[-\d.e+]+,[-\d.e+]+\n)+", c[3][0])
    # The curve's bytes but for the measured seconds; the printed lines but for the timing and file names.
    seconds = re.compile(rb'\n "seconds": [\d.e+-]+,\n')
    assert seconds.search(c[3][1]) and seconds.search(python[3][1])
    assert seconds.sub(b"", c[3][1]) == seconds.sub(b"", python[3][1])
    assert b'"probes": 40\n  }\n ]' in c[3][1] and b'"mode": "%s"' % mode.encode() in c[3][1]
    timing = re.compile(r" in \d+\.\d\d s,")
    assert timing.search(c[1]) and timing.search(python[1])
    assert timing.sub("", c[1]) == timing.sub("", python[1])
    assert c[1].startswith("placed 40 probes in ")
    assert assert_progress_lines(c[2], "place") == assert_progress_lines(python[2], "place") == []


@needs_c_tool
def test_place_failures_match(tmp_path):
    scene = os.path.join(SCENES, "two_rooms.json")
    probes = tmp_path / "probes.csv"
    usage_errors = [["--mode", "flying"], ["--target", "-3"], ["--spacing", "wide"], ["--curve"]]
    for extra in usage_errors:
        c, python = both(tmp_path, "place", scene, "-o", probes, *extra, files=[probes])
        assert c[0] == python[0] == 2 and c[3] == python[3] == [None], extra
        assert c[2].splitlines()[0] == python[2].splitlines()[0], extra
    c, python = both(tmp_path, "place", scene, files=[probes])
    assert c[0] == python[0] == 2 and c[2].splitlines()[0] == python[2].splitlines()[0]
    failures = [["--target", "500", "--rays", "8", "--threads", "1"], ["--spacing", "0"], ["--rays", "0"],
                ["--margin", "100"]]
    for extra in failures:
        c, python = both(tmp_path, "place", scene, "-o", probes, *extra, files=[probes])
        assert c[0] == python[0] == 1 and c[1] == python[1] == "" and c[3] == python[3] == [None], extra
        messages = [line for line in c[2].splitlines() if "%" not in line]
        assert messages == [line for line in python[2].splitlines() if "%" not in line], extra
        assert len(messages) == 1 and messages[0].startswith("tetprobe: error: "), extra
        if extra[1] == "500":
            assert "placing probes failed: TP_ERROR_INVALID_ARGUMENT: target_count 500 is more than" in messages[0]
    for args in (["place", tmp_path / "missing.json", "-o", probes],
                 ["place", scene, "-o", tmp_path / "no-such-dir" / "p.csv", "--spacing", "2", "--rays", "8"]):
        c, python = both(tmp_path, *args)
        assert c[0] == python[0] == 1 and c[1] == python[1] == ""
        messages = [line for line in c[2].splitlines() if "%" not in line]
        assert messages == [line for line in python[2].splitlines() if "%" not in line] and len(messages) == 1
    assert messages[0].startswith("tetprobe: error: cannot write ")


@needs_c_tool
def test_failures_and_usage_errors_match(tmp_path):
    garbage = tmp_path / "garbage.tpb"
    garbage.write_bytes(b"\x00" * 300)
    probe_csv(tmp_path / "probes.csv", 12)
    failures = [["info", tmp_path / "missing.tpb"], ["query", garbage, 0, 0, 0],
                ["build", tmp_path / "probes.csv", "-o", tmp_path / "no-such-dir" / "x.tpb"],
                ["bake", tmp_path / "missing.json", "-o", tmp_path / "x.tpb"],
                ["plan", tmp_path / "missing.json"], ["version"]]
    for args in failures:
        assert_same(*both(tmp_path, *args))
    usage_errors = [["query", garbage, "x", 0, 0], ["query", garbage, "1e999", 0, 0], ["query", garbage, 1, 2],
                    ["build", tmp_path / "probes.csv", "-o", tmp_path / "x.tpb", "--compactt"], ["build", "-o"],
                    ["bake", "scene.json", "-o", "x", "--rays", "zero"],
                    ["bake", "scene.json", "-o", "x", "--rays", "0"],
                    ["bake", "scene.json", "-o", "x", "--seed", "-1"], ["plan"], ["frobnicate"], []]
    for args in usage_errors:
        c, python = both(tmp_path, *args)
        assert c[0] == python[0] == 2, args
        # The first line says what is wrong; the usage text below it lists `demo` only in the C tool.
        assert c[2].splitlines()[0] == python[2].splitlines()[0], args
        assert "usage:" in python[2]
    assert both(tmp_path, "--help")[1][0] == 0


def test_nlohmann_number_spelling():
    # Grisu2 is not always shortest: repr(-0.3899074196815491) has 16 digits, nlohmann prints 17.
    assert cli.dump_json(-0.3899074196815491) == "-0.38990741968154907"
    assert cli.dump_json(5e-324) == "5e-324" and cli.dump_json(1.7976931348623157e308) == "1.7976931348623157e+308"
    assert [cli.dump_json(v) for v in (1.0, 100.0, 0.5, -0.0, 1e-05, 0.0001, 1e15, 1e16, 1.5e-7, 2.5e300)] == \
        ["1.0", "100.0", "0.5", "-0.0", "1e-05", "0.0001", "1e+15", "1e+16", "1.5e-07", "2.5e+300"]
    assert cli.dump_json(123456789012345.0) == "123456789012345.0"
    assert cli.dump_json(float("nan")) == "null"
    assert cli.dump_json({"a": [1, True, "x\n"], "b": []}, 2) == \
        '{\n  "a": [\n    1,\n    true,\n    "x\\n"\n  ],\n  "b": []\n}'
    assert cli.dump_json([3, 4, 5]) == "[3,4,5]"


def test_python_m_tetprobe_runs_the_same_main(tmp_path):
    status, out, err = run([sys.executable, "-m", "tetprobe"], ["version"])
    assert (status, err) == (0, "") and out == "tetprobe %d.%d.%d\n" % cli.library_version()
    status, out, err = run([sys.executable, "-m", "tetprobe"], ["info", tmp_path / "missing.tpb"])
    assert status == 1 and out == "" and err.startswith("tetprobe: error: loading the store failed: TP_ERROR_IO: ")
    status, out, err = run([sys.executable, "-m", "tetprobe"], [])
    assert status == 2 and err == cli.USAGE
