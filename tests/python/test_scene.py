"""Scene, bake and bake_plan against answers known without the code."""
import json
import math
import os
import shlex
import subprocess

import numpy as np
import pytest

from tetprobe import Error, Scene, Status, Store, bake, bake_plan, sh

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "samples", "scenes")

QUAD = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float32)
QUAD_TRIANGLES = np.array([[0, 2, 1], [0, 3, 2]], dtype=np.uint32)


def test_uniform_sky_gives_the_constant_radiance_sh():
    scene = Scene()
    scene.set_sky(color=(0.5, 0.25, 1.0))
    positions = np.array([[0, 0, 0], [10, -3, 2]], dtype=np.float32)
    out = bake(scene, positions, rays=64, bounces=1)
    expected = sh.ambient((0.5, 0.25, 1.0))
    assert out.shape == (2, 27)
    assert np.allclose(out, expected, atol=1e-3 * expected[0])
    scene.set_sky(sh=expected)
    assert np.allclose(bake(scene, positions, rays=64), expected, atol=1e-3 * expected[0])
    plan = bake_plan(scene, positions)
    assert plan["sky"] and plan["lights"] == 0 and plan["bounces"] == 0 and "sky" in plan["text"]


def test_unoccluded_directional_light_is_the_analytic_delta():
    scene = Scene()
    direction = np.array([0.3, -1.0, 0.2])
    direction /= np.linalg.norm(direction)
    scene.add_directional_light(direction, color=(1.0, 0.5, 0.25), intensity=2.0)
    out = bake(scene, np.zeros((1, 3), dtype=np.float32), rays=16, bounces=0)
    expected = sh.directional(direction, 2.0 * np.array([1.0, 0.5, 0.25]))
    assert np.allclose(out[0], expected, atol=1e-4)


def test_point_light_follows_the_inverse_square_law():
    scene = Scene()
    scene.add_point_light((0, 0, 0), color=(1, 1, 1), intensity=4.0)
    positions = np.array([[1, 0, 0], [0, 2, 0], [0, 0, -4]], dtype=np.float32)
    out = bake(scene, positions, rays=16, bounces=0)
    irradiance_facing = [sh.eval_irradiance(out[i], -positions[i] / np.linalg.norm(positions[i]))[0] / 1.0625
                         for i in range(3)]
    assert np.allclose(irradiance_facing, [4.0, 1.0, 0.25], rtol=1e-3)


def test_an_occluder_removes_the_light_and_culling_changes_nothing():
    scene = Scene()
    scene.add_mesh(QUAD * 5 + np.array([0, 2, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0, 0, 0))
    scene.add_directional_light((0, -1, 0), color=(1, 1, 1), intensity=3.0)
    positions = np.array([[0, 0, 0], [20, 0, 0]], dtype=np.float32)
    out = bake(scene, positions, rays=32, bounces=0)
    assert abs(out[0, 0]) < 1e-6                      # under the roof: no sun
    assert out[1, 0] == pytest.approx(3.0 * 0.282095, rel=1e-3)  # beside it: the sun
    same = bake(scene, positions, rays=32, bounces=0, culling=False)
    assert np.array_equal(out, same)


def test_realtime_light_contributes_only_bounced_light():
    scene = Scene()
    scene.add_directional_light((0, -1, 0), color=(1, 1, 1), intensity=3.0, mode="realtime")
    positions = np.zeros((1, 3), dtype=np.float32)
    assert np.allclose(bake(scene, positions, rays=32, bounces=2), 0.0)
    scene.add_mesh(QUAD * 50 + np.array([0, -1, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0.5, 0.5, 0.5))
    plan = bake_plan(scene, positions, bounces=2)
    assert plan["realtime_lights"] == 1 and plan["direct_lights"] == 0
    out = bake(scene, positions, rays=256, bounces=1)
    down = sh.eval_irradiance(out[0], (0, -1, 0))[0]
    # Light from a lit floor below: irradiance facing it is about albedo * E (a large floor).
    assert 0.5 * 3.0 * 0.7 < down < 0.5 * 3.0 * 1.2


def test_same_seed_gives_the_same_bytes_whatever_the_thread_count():
    scene = Scene()
    scene.add_mesh(QUAD * 3 + np.array([0, -1, 0], dtype=np.float32), QUAD_TRIANGLES, albedo=(0.7, 0.7, 0.7))
    scene.add_point_light((0, 2, 0), (1, 1, 1), intensity=5.0)
    scene.set_sky(color=(0.1, 0.2, 0.3))
    rng = np.random.default_rng(1)
    positions = rng.uniform(-1, 1, (16, 3)).astype(np.float32) * np.array([1, 0.5, 1], dtype=np.float32)
    a = bake(scene, positions, rays=64, bounces=2, seed=7, threads=1)
    b = bake(scene, positions, rays=64, bounces=2, seed=7, threads=2)
    assert a.tobytes() == b.tobytes()


def test_scene_probes_bake_into_a_store():
    scene = Scene()
    scene.set_sky(color=(1, 1, 1))
    rng = np.random.default_rng(2)
    scene.probes = rng.random((20, 3)).astype(np.float32)
    assert scene.probes.shape == (20, 3)
    baked = bake(scene, rays=32)
    store = Store.build(scene.probes, baked)
    value, _ = store.interpolate([0.5, 0.5, 0.5])
    assert value[0] == pytest.approx(math.sqrt(4 * math.pi), rel=2e-3)


def test_progress_and_cancel():
    scene = Scene()
    scene.set_sky(color=(1, 1, 1))
    positions = np.zeros((4, 3), dtype=np.float32)
    seen = []
    bake(scene, positions, rays=32, progress=lambda f, stage: seen.append(f))
    assert seen and all(0.0 <= f <= 1.0 for f in seen)
    with pytest.raises(Error) as raised:
        bake(scene, positions, rays=32, progress=lambda f, stage: True)
    assert raised.value.status == Status.CANCELLED


def test_scene_errors(tmp_path):
    scene = Scene()
    with pytest.raises(Error):
        scene.add_mesh(QUAD, np.array([[0, 1, 9]]))
    nan_quad = QUAD.copy()
    nan_quad[1, 1] = np.nan
    with pytest.raises(Error):
        scene.add_mesh(nan_quad, QUAD_TRIANGLES)
    with pytest.raises(Error):
        scene.add_point_light((0, 0, 0), (1, 1, 1), intensity=-1.0)
    with pytest.raises(ValueError, match="mode"):
        scene.add_point_light((0, 0, 0), (1, 1, 1), mode="sometimes")
    with pytest.raises(ValueError, match="color and sh"):
        scene.set_sky()
    with pytest.raises(Error):
        bake(scene, np.zeros((2, 3), dtype=np.float32), rays=0)
    with pytest.raises(Error):
        Scene.load(str(tmp_path / "missing.json"))
    broken = tmp_path / "broken.json"
    broken.write_text('{"meshes": [ {"vertices": [1, 2,')
    with pytest.raises(Error) as raised:
        Scene.load(str(broken))
    assert raised.value.status == Status.SCENE and "broken.json" in raised.value.message


@pytest.mark.parametrize("name", ["cornell_box.json", "two_rooms.json", "race_track.json"])
def test_sample_scenes_load_and_plan(name):
    path = os.path.join(SCENES, name)
    if not os.path.exists(path):
        pytest.skip("%s not in samples/scenes yet" % name)
    scene = Scene.load(path)
    assert len(scene.probes) > 0
    plan = bake_plan(scene)
    assert plan["meshes"] > 0 and plan["text"]


# ---- scene files through Assimp (docs/scene-format.md)

def _without_sky(tmp_path):
    """two_rooms.json without its sky, its OBJ placed by absolute path: what two_rooms.gltf can say."""
    with open(os.path.join(SCENES, "two_rooms.json")) as f:
        document = json.load(f)
    del document["sky"]
    document["meshes"][0]["file"] = os.path.abspath(os.path.join(SCENES, document["meshes"][0]["file"]))
    path = tmp_path / "two_rooms_no_sky.json"
    path.write_text(json.dumps(document))
    return str(path), np.array(document["probes"], dtype=np.float32)


def test_the_gltf_two_rooms_bake_as_the_json_two_rooms(tmp_path):
    # The same triangles and materials; the sun's direction passes through a quaternion, so the lights
    # agree to float rounding, and the bakes (same seed) within that: the relative L0 difference stays
    # below 1e-5 at every probe (it was 1.7e-7 at most, and 0 at 64 of the 94 probes, when written).
    json_path, probes = _without_sky(tmp_path)
    from_gltf = Scene.load(os.path.join(SCENES, "two_rooms.gltf"))
    from_json = Scene.load(json_path)
    assert from_gltf.up == "+y" and from_gltf.notes == [] and len(from_gltf.probes) == 0
    a = bake(from_gltf, probes, rays=128, seed=3)
    b = bake(from_json, probes, rays=128, seed=3)
    l0 = np.abs(b[:, [0, 9, 18]]).sum(axis=1)
    assert l0.min() > 0
    relative = np.abs(a[:, [0, 9, 18]] - b[:, [0, 9, 18]]).sum(axis=1) / l0
    assert relative.max() < 1e-5, relative.max()
    plan = bake_plan(from_gltf, probes)
    assert plan["meshes"] == 2 and plan["lights"] == 2


def test_scale_keeps_the_irradiance_at_the_scaled_place_and_up_is_recorded():
    path = os.path.join(SCENES, "two_rooms.gltf")
    probes = np.array([[2, 1.2, 2], [6, 1, 1], [4.1, 1, 2]], dtype=np.float32)
    metres = Scene.load(path)
    doubled = Scene.load(path, scale=2.0, up="+z")
    assert doubled.up == "+z" and metres.up == "+y"
    # Twice the size, point intensities four times: the same SH at the doubled places, bit for bit
    # (every length doubles exactly in binary floating point).
    a = bake(metres, probes, rays=256, seed=5)
    b = bake(doubled, 2 * probes, rays=256, seed=5)
    assert np.array_equal(a, b)
    metres.up = "-x"
    assert metres.up == "-x"
    with pytest.raises(ValueError, match="up"):
        metres.up = "north"
    with pytest.raises(TypeError, match="up"):
        Scene.load(path, up=3)
    with pytest.raises(TypeError, match="scale"):
        Scene.load(path, scale="big")
    with pytest.raises(ValueError, match="scale"):
        Scene.load(path, scale=-1.0)
    assert Scene().up == "+y" and Scene().notes == []


def test_notes_and_bad_files(tmp_path):
    bare = tmp_path / "bare.obj"
    bare.write_text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n")
    notes = Scene.load(str(bare)).notes
    assert len(notes) == 1 and "bare.obj" in notes[0] and "default" in notes[0]

    def scene_error(name, content, *words):
        path = tmp_path / name
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content)
        with pytest.raises(Error) as raised:
            Scene.load(str(path))
        assert raised.value.status == Status.SCENE, raised.value.message
        for word in (name,) + words:
            assert word in raised.value.message, raised.value.message

    with open(os.path.join(SCENES, "two_rooms.gltf")) as f:
        rooms = json.load(f)
    scene_error("malformed.gltf", '{"asset": {"version": "2.0"}, "nodes": [', "malformed")
    scene_error("truncated.glb", b"glTF\x02\x00\x00\x00\x00\x10\x00\x00", "truncated")
    rooms["extensions"]["KHR_lights_punctual"]["lights"][0]["type"] = "area"
    scene_error("area.gltf", json.dumps(rooms), "unknown type", "area")
    scene_error("missing_mtl.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n", "gone.mtl")
    scene_error("no_intensity.json", '{"lights": [{"type": "point", "position": [0, 0, 0]}]}', "intensity")
    scene_error("placing.json", '{"meshes": [{"file": "nowhere.glb"}]}', "nowhere.glb")
    with pytest.raises(Error) as raised:
        Scene.load(str(tmp_path / "absent.gltf"))
    assert raised.value.status == Status.IO


# ---- the command line chains its own steps (TETPROBE_CLI)

CLI = os.environ.get("TETPROBE_CLI", "")
needs_cli = pytest.mark.skipif(not (CLI and os.path.exists(CLI)), reason="TETPROBE_CLI is not set")
REPO = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))


def _run(*args, cwd=None, expect=0):
    result = subprocess.run([CLI] + [str(a) for a in args], capture_output=True, text=True, cwd=cwd)
    assert result.returncode == expect, result.stdout + result.stderr
    return result


def _markdown_section(path, heading):
    with open(path) as f:
        text = f.read()
    start = text.index(heading)
    end = text.find("\n## ", start + len(heading))
    return text[start:end if end >= 0 else len(text)]


@needs_cli
def test_the_readme_chain_runs_exactly_as_printed(tmp_path):
    # Every command of the README's "From a level to a store" section, in a folder where
    # build/samples/tetprobe is this build's tool and samples/ is the repository's.
    section = _markdown_section(os.path.join(REPO, "README.md"), "## From a level to a store")
    commands = [line.strip() for line in section.splitlines() if line.strip().startswith("build/samples/tetprobe ")]
    assert len(commands) >= 8, commands
    os.makedirs(tmp_path / "build" / "samples")
    os.symlink(CLI, tmp_path / "build" / "samples" / "tetprobe")
    os.symlink(os.path.join(REPO, "samples"), tmp_path / "samples")
    outputs = []
    for command in commands:
        result = subprocess.run(shlex.split(command), capture_output=True, text=True, cwd=tmp_path)
        assert result.returncode == 0, command + "\n" + result.stdout + result.stderr
        outputs.append(result.stdout)
    # Both chains end in a query inside the rooms, answered by a store built with leak control.
    queries = [o for c, o in zip(commands, outputs) if " query " in c]
    builds = [o for c, o in zip(commands, outputs) if " build " in c]
    assert len(queries) == 2 and len(builds) == 2
    assert all("leak control:" in o for o in builds)
    for o in queries:
        irradiance = [float(v) for v in o.split("irradiance")[1].split("(")[0].split()]
        assert len(irradiance) == 3 and min(irradiance) > 0


@needs_cli
def test_bake_takes_a_probe_file_and_writes_one(tmp_path):
    scene = os.path.join(SCENES, "two_rooms.json")
    probes = tmp_path / "probes.csv"
    probes.write_text("2,1.2,2\n6,1,1\n4.1,1,2\n")
    _run("bake", scene, "--probes", probes, "-o", tmp_path / "baked.csv", "--rays", 64, "--seed", 2)
    rows = np.loadtxt(tmp_path / "baked.csv", delimiter=",", dtype=np.float32, ndmin=2)
    assert rows.shape == (3, 30)
    assert np.array_equal(rows[:, :3], np.loadtxt(probes, delimiter=",", dtype=np.float32))
    # The same bake through the library: the file holds its floats to the bit.
    expected = bake(Scene.load(scene), rows[:, :3], rays=64, seed=2)
    assert np.array_equal(rows[:, 3:], expected)
    # Baked straight into a store, and the store built from the file with leak control.
    _run("bake", scene, "--probes", probes, "-o", tmp_path / "direct.tpb", "--rays", 64, "--seed", 2)
    out = _run("build", tmp_path / "baked.csv", "--scene", scene, "-o", tmp_path / "leak.tpb").stdout
    assert "leak control:" in out
    info = json.loads(_run("info", tmp_path / "leak.tpb", "--json").stdout)
    assert info["probes"] == 3
    # plan reads the probe file too; place, bake and plan read a glTF and an OBJ, with --scale and --up.
    assert "effects plan" in _run("plan", os.path.join(SCENES, "two_rooms.gltf"), "--probes", probes).stdout
    _run("plan", os.path.join(SCENES, "two_rooms.gltf"), "--probes", probes, "--scale", 1, "--up", "+y")
    bare = tmp_path / "bare.obj"
    bare.write_text("v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n")
    noted = _run("plan", bare, "--probes", probes)
    assert "note:" in noted.stderr and "default" in noted.stderr
    failed = _run("plan", os.path.join(SCENES, "two_rooms.gltf"), "--probes", probes, "--up", "north", expect=2)
    assert "--up" in failed.stderr
    failed = _run("build", tmp_path / "baked.csv", "-o", tmp_path / "x.tpb", "--scale", 2, expect=2)
    assert "--scene" in failed.stderr


@needs_cli
def test_the_probe_file_document_example_builds(tmp_path):
    # docs/probe-file.md's CSV example, exactly: four probes of a white sky of radiance 1, one with an
    # L1 term; tetprobe build reads it and the store answers the probes' own SH at the probes.
    section = _markdown_section(os.path.join(REPO, "docs", "probe-file.md"), "## CSV")
    example = section.split("```csv\n")[1].split("```")[0]
    path = tmp_path / "example.csv"
    path.write_text(example)
    _run("build", path, "-o", tmp_path / "example.tpb")
    store = Store.load(str(tmp_path / "example.tpb"))
    assert store.info()["probes"] == 4
    rows = np.array([[float(v) for v in line.split(",")] for line in example.splitlines() if not line.startswith("#")],
                    dtype=np.float32)
    got, _ = store.interpolate(rows[:, :3])
    assert np.allclose(got, rows[:, 3:], atol=2e-3)
    assert rows[0, 3] == pytest.approx(2 * math.sqrt(math.pi), rel=1e-7)


def test_a_lights_near_distance_holds_its_irradiance_inside_it():
    def irradiance_at(near_distance):
        scene = Scene()
        scene.add_mesh(QUAD * 10 + np.array([0, -5, 0], dtype=np.float32), QUAD_TRIANGLES)
        scene.add_point_light((0, 0, 0), (1, 1, 1), intensity=1.0, near_distance=near_distance)
        out = bake(scene, np.array([[0.2, 0, 0]], dtype=np.float32), rays=16, bounces=0)
        return sh.eval_irradiance(out[0], (-1, 0, 0))[0]
    # Direct light only, no noise: the inverse square at 0.2 against the one held at 0.5.
    assert irradiance_at(0.0) / irradiance_at(0.5) == pytest.approx((0.5 / 0.2) ** 2, rel=1e-4)
    with pytest.raises(Error, match="near distance"):
        Scene().add_point_light((0, 0, 0), (1, 1, 1), near_distance=-1.0)
