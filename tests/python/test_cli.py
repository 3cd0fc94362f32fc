"""The `tetprobe` command (path in $TETPROBE_CLI): build from CSV and JSON, info, query, errors."""
import json
import os
import re
import subprocess

import numpy as np
import pytest

from tetprobe import Store

CLI = os.environ.get("TETPROBE_CLI", "")
pytestmark = pytest.mark.skipif(not (CLI and os.path.exists(CLI)), reason="TETPROBE_CLI is not set")


def run(*args, ok=True):
    result = subprocess.run([CLI] + [str(a) for a in args], capture_output=True, text=True, timeout=120)
    if ok:
        assert result.returncode == 0, result.stderr
    return result


def probes(n=40, seed=3):
    rng = np.random.default_rng(seed)
    positions = rng.random((n, 3)).astype(np.float32) * 4
    sh = rng.uniform(-1, 1, (n, 27)).astype(np.float32)
    return positions, sh


def test_build_from_csv_then_info_and_query(tmp_path):
    positions, sh = probes()
    csv = tmp_path / "probes.csv"
    lines = ["x,y,z," + ",".join("sh%d" % k for k in range(27))]
    lines += [",".join("%.9g" % v for v in np.concatenate([p, s])) for p, s in zip(positions, sh)]
    csv.write_text("\n".join(lines) + "\n")
    store_path = tmp_path / "probes.tpb"
    out = run("build", csv, "-o", store_path).stdout
    assert "40 probes" in out and "fast layout" in out
    assert Store.load(str(store_path)).to_bytes() == Store.build(positions, sh).to_bytes()

    info = json.loads(run("info", store_path, "--json").stdout)
    assert info["probes"] == 40 and info["cells"] == info["inner_cells"] + info["outer_cells"]
    assert info["bytes"] == store_path.stat().st_size
    assert info["format_version"] == 6 and info["layout"] == "fast"
    text = run("info", store_path).stdout
    assert "probes:" in text and "index_bits:" in text and 'layout:         "fast"' in text

    compact_path = tmp_path / "compact.tpb"
    out = run("build", csv, "-o", compact_path, "--compact").stdout
    assert "40 probes" in out and "compact layout" in out
    assert Store.load(str(compact_path)).to_bytes() == Store.build(positions, sh, compact=True).to_bytes()
    compact_info = json.loads(run("info", compact_path, "--json").stdout)
    assert compact_info["layout"] == "compact" and compact_info["bytes"] < info["bytes"]
    assert compact_info["cells"] == info["cells"]
    assert 'layout:         "compact"' in run("info", compact_path).stdout

    small_path = tmp_path / "small.tpb"
    out = run("build", csv, "-o", small_path, "--compact", "--sh-encoding", "unorm8_l1", "--quantize-positions").stdout
    assert "compact layout, unorm8_l1 SH, quantised positions" in out
    expected_small = Store.build(positions, sh, compact=True, sh_encoding="unorm8_l1", quantize_positions=True)
    assert Store.load(str(small_path)).to_bytes() == expected_small.to_bytes()
    small_info = json.loads(run("info", small_path, "--json").stdout)
    assert small_info["sh_encoding"] == "unorm8_l1" and small_info["quantized_positions"] is True
    assert sum(small_info["section_bytes"].values()) == small_info["bytes"] == small_path.stat().st_size
    assert small_info["section_bytes"]["sh"] == 40 * 15 and small_info["section_bytes"]["positions"] == 40 * 6
    extent = positions.max(axis=0).astype(np.float64) - positions.min(axis=0)
    assert all(e / 65534 <= step < 2 * e / 65534 for step, e in zip(small_info["position_step"], extent))
    rebuilt_path = tmp_path / "rebuilt.tpb"
    out = run("build", csv, "-o", rebuilt_path, "--layout", "rebuilt", "--sh-encoding", "unorm8", "--quantize-positions").stdout
    assert "rebuilt layout, unorm8 SH" in out
    expected_rebuilt = Store.build(positions, sh, layout="rebuilt", sh_encoding="unorm8", quantize_positions=True)
    assert Store.load(str(rebuilt_path)).to_bytes() == expected_rebuilt.to_bytes()
    rebuilt_info = json.loads(run("info", rebuilt_path, "--json").stdout)
    assert rebuilt_info["layout"] == "rebuilt" and rebuilt_info["section_bytes"]["cells"] == 0
    assert rebuilt_info["cells"] == info["cells"]
    for wrong in (["--layout", "tiny"], ["--compact", "--layout", "rebuilt"]):
        refused = run("build", csv, "-o", tmp_path / "no.tpb", *wrong, ok=False)
        assert refused.returncode == 2 and "--layout" in refused.stderr + refused.stdout
    refused = run("build", csv, "-o", tmp_path / "no.tpb", "--sh-encoding", "float8", ok=False)
    assert refused.returncode == 2 and "--sh-encoding" in refused.stderr and not (tmp_path / "no.tpb").exists()

    point = positions[:4].mean(axis=0)
    answer = json.loads(run("query", store_path, *point, "--weights", "--json").stdout)
    expected, _ = Store.build(positions, sh).interpolate(point)
    assert np.allclose(answer["sh"], expected, atol=1e-5)
    compact_answer = json.loads(run("query", compact_path, *point, "--weights", "--json").stdout)
    assert compact_answer["cell"] == answer["cell"] and np.allclose(compact_answer["sh"], answer["sh"], atol=1e-5)
    assert abs(sum(answer["weights"]) - 1.0) < 1e-5
    plain = run("query", store_path, *point, "--weights").stdout
    assert "weight" in plain and "cell" in plain
    far = json.loads(run("query", store_path, "-100", "2", "2", "--json").stdout)
    assert far["cell_kind"] == "outer"


def test_build_from_json_without_sh(tmp_path):
    positions, _ = probes(12, 5)
    source = tmp_path / "probes.json"
    source.write_text(json.dumps({"probes": positions.tolist()}))
    store_path = tmp_path / "out.tpb"
    run("build", source, "-o", store_path)
    answer = json.loads(run("query", store_path, 1, 1, 1, "--json").stdout)
    assert answer["sh"] == [0.0] * 27


def test_errors_are_messages_and_non_zero_exits(tmp_path):
    result = run("info", tmp_path / "missing.tpb", ok=False)
    assert result.returncode == 1 and "TP_ERROR_IO" in result.stderr
    garbage = tmp_path / "garbage.tpb"
    garbage.write_bytes(b"\x00" * 300)
    result = run("query", garbage, 0, 0, 0, ok=False)
    assert result.returncode == 1 and "TP_ERROR_INVALID_BLOB" in result.stderr
    bad_csv = tmp_path / "bad.csv"
    bad_csv.write_text("0,0,0\n1,2\n")
    result = run("build", bad_csv, "-o", tmp_path / "x.tpb", ok=False)
    assert result.returncode == 1 and "bad.csv:2" in result.stderr
    assert not (tmp_path / "x.tpb").exists()
    nan_csv = tmp_path / "nan.csv"
    nan_csv.write_text("0,0,0\n1,nan,0\n")
    result = run("build", nan_csv, "-o", tmp_path / "x.tpb", ok=False)
    assert result.returncode == 1 and "TP_ERROR_INVALID_ARGUMENT" in result.stderr
    assert run("query", garbage, "x", 0, 0, ok=False).returncode == 2
    assert run("build", bad_csv, "-o", tmp_path / "x.tpb", "--compactt", ok=False).returncode == 2
    assert run("frobnicate", ok=False).returncode == 2
    assert run(ok=False).returncode == 2
    result = run("build", bad_csv, "-o", "/nonexistent-dir/x.tpb", ok=False)
    assert result.returncode == 1


def test_demo_writes_its_pictures_and_stores(tmp_path):
    out = tmp_path / "demo"
    result = run("demo", "--out", out, "--rays", "16", "--bounces", "1")
    assert "mean steps per query" in result.stdout and "max SH error" in result.stdout
    png = (out / "analytic_irradiance.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert Store.load(str(out / "analytic.tpb")).info()["probes"] > 100
    assert not [p for p in out.iterdir() if ".tmp" in p.name]
    for name in ("analytic_irradiance.png", "two_rooms_irradiance.png", "two_rooms_leak_fix.png"):
        _assert_framed_with_colour_bar(out / name)
    _assert_leak_picture_shows_the_wall_and_the_difference(out / "two_rooms_leak_fix.png", result.stdout)


def _assert_leak_picture_shows_the_wall_and_the_difference(path, stdout):
    """Three panels (without, with, their difference), the wall in grey in each, and a diverging colour bar for the
    difference (dark red at the top, dark blue at the bottom) whose panel holds both signs."""
    image = pytest.importorskip("matplotlib.image").imread(str(path))[:, :, :3]
    grey = np.abs(image - 150 / 255).max(axis=2) < 0.01
    columns = np.nonzero(grey.any(axis=0))[0]
    # The wall (x 4.0 to 4.2 m) appears once per panel: three runs of grey columns.
    runs = np.split(columns, np.nonzero(np.diff(columns) > 40)[0] + 1)
    walls = [r for r in runs if grey[:, r].sum() > 300]
    assert len(walls) == 3, [(r[0], r[-1], grey[:, r].sum()) for r in runs]
    red, blue = np.array([0.40, 0.0, 0.12]), np.array([0.02, 0.19, 0.38])
    near = lambda colour: np.abs(image - colour).max(axis=2) < 0.02  # noqa: E731
    bar_columns = np.nonzero(near(red).any(axis=0) & near(blue).any(axis=0))[0]
    assert len(bar_columns) >= 10, "no diverging colour bar"
    column = bar_columns[0]
    rows = np.nonzero(near(red)[:, column] | near(blue)[:, column])[0]
    assert near(red)[rows[0], column] and near(blue)[rows[-1], column]  # red on top: without - with > 0
    # Beside the wall in the difference panel: light that leaked east is gone (red), the west side brightens (blue).
    beside = image[:, walls[2][0] - 40:walls[2][-1] + 40]
    reddish = (beside[:, :, 0] - beside[:, :, 2] > 0.25).sum()
    bluish = (beside[:, :, 2] - beside[:, :, 0] > 0.25).sum()
    # (The west band is the narrower: with the wall's plane judging the side, only the cells whose edges cross the
    # wall change, and the west side's change is the smaller; 74 strongly blue pixels against 527 red on 2026-11-25.)
    assert reddish > 100 and bluish > 40, (reddish, bluish)
    change = re.search(r"the largest change, (-?[0-9.]+) of irradiance ([0-9.]+)", stdout)
    assert change and abs(float(change.group(1))) > 0.1 * float(change.group(2)), stdout


def _assert_framed_with_colour_bar(path):
    """The picture has a white frame with black text (ticks, labels) and, on the right, a colour bar
    running from the ramp's top colour (near white) down to its bottom colour (dark blue)."""
    image = pytest.importorskip("matplotlib.image").imread(str(path))[:, :, :3]
    height, width = image.shape[:2]
    assert (image[0, 0] == 1).all() and (image[-1, -1] == 1).all()
    bottom_margin = image[height - 30:]
    assert (bottom_margin.sum(axis=2) == 0).any(), "no black text under the panels"
    # The bar is the rightmost column holding the ramp's darkest colour (0.02, 0.02, 0.15) low down.
    dark = np.abs(image - np.array([0.02, 0.02, 0.15])).max(axis=2) < 0.02
    rows, columns = np.nonzero(dark)
    column = columns.max()
    bar = image[:, column]
    coloured = np.nonzero((np.abs(bar - 1).max(axis=1) > 0.01) & (bar.max(axis=1) > 0))[0]  # not frame or text
    top, bottom = bar[coloured[0]], bar[coloured[-1]]
    assert top.min() > 0.8, top
    assert np.abs(bottom - np.array([0.02, 0.02, 0.15])).max() < 0.02, bottom


SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")


def test_bake_a_sample_scene_into_a_store(tmp_path):
    scene = os.path.join(SCENES, "cornell_box.json")
    if not os.path.exists(scene):
        pytest.skip("samples/scenes/cornell_box.json not present")
    store_path = tmp_path / "cornell.tpb"
    result = run("bake", scene, "-o", store_path, "--rays", "16", "--bounces", "1", "--seed", "3", "--threads", "1")
    assert "effects plan:" in result.stdout and "emissive" in result.stdout
    assert "baked" in result.stdout and "wrote" in result.stdout
    assert "100%" in result.stderr  # the progress bar
    store = Store.load(str(store_path))
    assert store.info()["input_probes"] > 0
    again = tmp_path / "again.tpb"
    run("bake", scene, "-o", again, "--rays", "16", "--bounces", "1", "--seed", "3", "--threads", "2")
    assert again.read_bytes() == store_path.read_bytes()  # same seed, any thread count
    result = run("bake", tmp_path / "missing.json", "-o", tmp_path / "x.tpb", ok=False)
    assert result.returncode == 1 and "x.tpb" not in os.listdir(tmp_path)
    assert run("bake", scene, "-o", tmp_path / "x.tpb", "--rays", "zero", ok=False).returncode == 2
