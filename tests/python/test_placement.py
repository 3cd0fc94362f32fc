"""Automatic probe placement and probes inside geometry, through the Python binding and the CLI."""
import json
import os
import subprocess

import numpy as np
import pytest

import tetprobe
from tetprobe import Error, Scene, Status

ROOM_LO, ROOM_HI = np.array([0, 0, 0], np.float32), np.array([6, 3, 6], np.float32)
PILLAR_LO, PILLAR_HI = np.array([2.5, 0, 2.5], np.float32), np.array([3.5, 3, 3.5], np.float32)
BOX_TRIANGLES = np.array([[0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5], [0, 1, 5], [0, 5, 4],
                          [2, 6, 7], [2, 7, 3], [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6]], np.uint32)


def box_vertices(lo, hi):
    return np.array([[hi[a] if corner & (1 << a) else lo[a] for a in range(3)] for corner in range(8)], np.float32)


def room_scene(two_sided_room=False):
    """A 6 x 3 x 6 room (faces in), a solid pillar (faces out, two-sided: closed, so solid) and a lamp."""
    scene = Scene()
    scene.add_mesh(box_vertices(ROOM_LO, ROOM_HI), BOX_TRIANGLES[:, ::-1].copy(), two_sided=two_sided_room)
    scene.add_mesh(box_vertices(PILLAR_LO, PILLAR_HI), BOX_TRIANGLES, two_sided=True)
    scene.add_point_light((0.6, 2.4, 0.6), (1, 1, 1), intensity=30)
    return scene


def distance_to_surfaces(points):
    """Distance from points inside the room to its walls and to the pillar's surface."""
    walls = np.minimum(points - ROOM_LO, ROOM_HI - points).min(axis=1)
    outside = np.maximum(np.maximum(PILLAR_LO - points, points - PILLAR_HI), 0)
    inside_depth = np.minimum(points - PILLAR_LO, PILLAR_HI - points).min(axis=1)
    in_pillar = np.all((points > PILLAR_LO) & (points < PILLAR_HI), axis=1)
    pillar = np.where(in_pillar, inside_depth, np.linalg.norm(outside, axis=1))
    return np.minimum(walls, pillar), in_pillar


def test_place_probes_obeys_the_rules_and_reports_its_curve():
    result = tetprobe.place_probes(room_scene(), spacing=0.75, margin=0.2, target=40, rays=64, bounces=1, seed=2)
    positions, curve = result
    assert positions.shape == (40, 3) and positions.dtype == np.float32
    distance, in_pillar = distance_to_surfaces(positions)
    assert not in_pillar.any()
    assert (distance >= 0.2).all()
    # One point per round, counts increasing to the result, errors estimated (non-negative).
    assert curve[-1, 0] == 40 and curve[0, 0] < 40 and (np.diff(curve[:, 0]) > 0).all()
    assert (curve[:, 1] >= 0).all() and curve[-1, 1] < curve[0, 1]
    # Deterministic for a seed whatever the thread count; a smaller target gets its own (exchanged) set,
    # after the same greedy rounds.
    again = tetprobe.place_probes(room_scene(), spacing=0.75, margin=0.2, target=40, rays=64, bounces=1, seed=2,
                                  threads=1)
    assert again.positions.tobytes() == positions.tobytes()
    assert again.error_curve.tobytes() == curve.tobytes()
    fewer = tetprobe.place_probes(room_scene(), spacing=0.75, margin=0.2, target=25, rays=64, bounces=1, seed=2)
    assert fewer.positions.shape == (25, 3) and fewer.error_curve[-1, 0] == 25
    rounds = fewer.error_curve[:-1]
    assert rounds.tobytes() == curve[:len(rounds)].tobytes()


def test_place_probes_error_bound_and_walkable():
    bounded = tetprobe.place_probes(room_scene(), spacing=0.75, margin=0.2, error_bound=0.6, rays=64, bounces=1)
    assert bounded.error_curve[-1, 1] <= 0.6 < bounded.error_curve[-2, 1]
    assert bounded.positions.shape[0] == bounded.error_curve[-1, 0]
    walkable = tetprobe.place_probes(room_scene(), mode="walkable", walk_height=(0.0, 1.0), spacing=0.75, margin=0.2,
                                     error_bound=0)
    assert walkable.positions.shape[0] > 20 and walkable.error_curve.shape[0] == 0  # every candidate, unbaked
    assert (walkable.positions[:, 1] <= 1.0).all()  # within the band above the floor (y = 0)


def courtyard():
    """An 8 x 8 courtyard open to the sky, walls 3 high, lit by a low sun: the south wall's shadow cuts the
    air above the floor with a sharp edge."""
    scene = Scene()
    scene.add_mesh(np.array([[0, 0, 0], [0, 0, 8], [8, 0, 8], [8, 0, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]], np.uint32), two_sided=False)
    quad = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
    for wall in ([[0, 0, 0], [8, 0, 0], [8, 3, 0], [0, 3, 0]], [[8, 0, 8], [0, 0, 8], [0, 3, 8], [8, 3, 8]],
                 [[0, 0, 8], [0, 0, 0], [0, 3, 0], [0, 3, 8]], [[8, 0, 0], [8, 0, 8], [8, 3, 8], [8, 3, 0]]):
        scene.add_mesh(np.array(wall, np.float32), quad, two_sided=False)
    direction = np.array([0.3, -0.6, 0.74])
    scene.add_directional_light(direction / np.linalg.norm(direction), (1, 1, 1), intensity=3)
    scene.set_sky(color=(0.25, 0.3, 0.4))
    return scene


LUMINANCE_NORMALS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], np.float64)


def luminance6(sh):
    """Luminance irradiance for the 6 axis normals of SH[N, 27] (the real-level benchmark's quantity)."""
    c0, c1, c2, c20, c22 = 0.282094791773878, 0.48860251190292, 1.092548430592079, 0.315391565252520, 0.546274215296039
    band = np.array([np.pi] + [2 * np.pi / 3] * 3 + [np.pi / 4] * 5)
    rows = []
    for x, y, z in LUMINANCE_NORMALS:
        basis = np.array([c0, c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z, c20 * (3 * z * z - 1), c2 * x * z,
                          c22 * (x * x - y * y)]) * band
        rows.append(np.concatenate([w * basis for w in (0.2126, 0.7152, 0.0722)]))
    return sh.astype(np.float64) @ np.array(rows).T


def measured_error(scene, probes, points, reference):
    """RMS over points and normals of |interpolated - reference| luminance irradiance over its mean, the
    probes baked with 256 rays."""
    sh = tetprobe.bake(scene, probes, rays=256, bounces=1, seed=99, threads=2)
    interpolated, _ = tetprobe.Store.build(probes, sh).interpolate(points)
    expected = luminance6(reference)
    return float(np.sqrt(((luminance6(interpolated) - expected) ** 2).mean()) / expected.mean())


def test_placement_beats_random_picks_and_reports_what_a_reference_measures():
    scene = courtyard()
    placed = tetprobe.place_probes(scene, mode="walkable", spacing=0.5, target=60, bounces=1, seed=3, threads=2)
    candidates = tetprobe.place_probes(scene, mode="walkable", spacing=0.5, error_bound=0).positions
    rng = np.random.default_rng(11)
    points = np.column_stack([rng.uniform(0.1, 7.9, 400), rng.uniform(0.1, 2.0, 400),
                              rng.uniform(0.1, 7.9, 400)]).astype(np.float32)
    reference = tetprobe.bake(scene, points, rays=1024, bounces=1, seed=12, threads=2)
    smart = measured_error(scene, placed.positions, points, reference)
    random = np.mean([measured_error(scene, candidates[np.random.default_rng(seed).choice(len(candidates), 60,
                                                                                          replace=False)],
                                     points, reference) for seed in (1, 2, 3)])
    assert smart < 0.8 * random, (smart, random)
    reported = placed.error_curve[-1, 1]
    assert 0.7 * smart < reported < 1.3 * smart, (reported, smart)


def test_playable_seeds_keep_the_space_they_reach():
    """Two closed rooms, not connected: a seed in the first keeps only its candidates."""
    scene = Scene()
    for lo, hi in (((0, 0, 0), (4, 3, 4)), ((6, 0, 0), (10, 3, 4))):
        scene.add_mesh(box_vertices(np.array(lo, np.float32), np.array(hi, np.float32)),
                       BOX_TRIANGLES[:, ::-1].copy(), two_sided=False)
    every = tetprobe.place_probes(scene, mode="walkable", error_bound=0).positions
    scene.set_playable_seeds(np.array([[1.2, 0.4, 2.1]], np.float32))
    reached = tetprobe.place_probes(scene, mode="walkable", error_bound=0).positions
    assert 0 < len(reached) == (every[:, 0] < 5).sum() < len(every)
    assert (reached[:, 0] < 5).all()
    scene.set_playable_seeds(np.zeros((0, 3), np.float32))
    assert len(tetprobe.place_probes(scene, mode="walkable", error_bound=0).positions) == len(every)
    scene.set_playable_seeds(np.array([[50, 0.5, 50]], np.float32))
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, mode="walkable", error_bound=0)
    assert error.value.status == Status.SCENE and "1 playable seeds" in str(error.value)


def test_place_probes_bad_input_and_cancel():
    scene = room_scene()
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, spacing=0)
    assert error.value.status == Status.INVALID_ARGUMENT and "spacing" in str(error.value)
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, spacing=0.75, target=100000)
    assert error.value.status == Status.INVALID_ARGUMENT and "target_count 100000" in str(error.value)
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, margin=50)
    assert error.value.status == Status.INVALID_ARGUMENT and "larger than the scene" in str(error.value)
    with pytest.raises(Error) as error:  # a spacing past what memory holds names the count
        tetprobe.place_probes(scene, spacing=0.0005)
    assert error.value.status == Status.INVALID_ARGUMENT and "raise the spacing" in str(error.value)
    with pytest.raises(Error) as error:  # one lattice point over the room: refused, never a silent single probe
        tetprobe.place_probes(scene, spacing=1000, target=1)
    assert error.value.status == Status.DEGENERATE and "1 points tested" in str(error.value)
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, spacing=0.75, target=40, rays=1)
    assert error.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(Error) as error:
        tetprobe.place_probes(scene, spacing=0.75, target=40, progress=lambda fraction, stage: stage == "select")
    assert error.value.status == Status.CANCELLED
    # A two-sided closed room is a solid block: nothing is left to place probes in.
    with pytest.raises(Error) as error:
        tetprobe.place_probes(room_scene(two_sided_room=True), spacing=0.75)
    assert error.value.status == Status.DEGENERATE
    sheet = Scene()
    sheet.add_mesh(np.array([[0, 0, 0], [0, 0, 4], [4, 0, 4], [4, 0, 0]], np.float32),
                   np.array([[0, 1, 2], [0, 2, 3]], np.uint32), two_sided=True)
    with pytest.raises(Error) as error:
        tetprobe.place_probes(sheet)
    assert error.value.status == Status.SCENE and "cannot be decided" in str(error.value)


def test_inside_probes_found_reported_dropped_and_pushed():
    scene = room_scene()
    positions = np.array([[1, 1, 1], [3, 1.5, 3], [2.6, 0.5, 3.4], [5, 2, 5]], np.float32)
    assert tetprobe.find_inside_probes(scene, positions).tolist() == [1, 2]
    plan = tetprobe.bake_plan(scene, positions, rays=16)
    assert plan["inside_probes"] == 2 and plan["inside_indices"] == [1, 2]
    assert "inside geometry: 2 probes (1, 2)" in plan["text"]
    kept = tetprobe.fix_inside_probes(scene, positions, "drop")
    assert kept.tolist() == positions[[0, 3]].tolist()
    pushed = tetprobe.fix_inside_probes(scene, positions, "push", margin=0.25)
    assert pushed.shape == positions.shape
    assert pushed[[0, 3]].tolist() == positions[[0, 3]].tolist()
    distance, in_pillar = distance_to_surfaces(pushed)
    assert not in_pillar.any() and (distance >= 0.25).all()
    # Probe 1 is 0.5 deep, probe 2 0.1 deep: each leaves through the nearest face.
    moved = np.linalg.norm(pushed - positions, axis=1)
    assert moved[1] == pytest.approx(0.75, abs=0.01) and moved[2] == pytest.approx(0.35, abs=0.01)
    with pytest.raises(ValueError, match="mode must be one of 'drop', 'push'"):
        tetprobe.fix_inside_probes(scene, positions, "teleport")
    with pytest.raises(Error) as error:
        tetprobe.fix_inside_probes(scene, positions, "push", margin=-1)
    assert error.value.status == Status.INVALID_ARGUMENT and "margin" in str(error.value)
    plan = tetprobe.bake_plan(scene, positions[[0, 3]], rays=16)
    assert plan["inside_probes"] == 0 and "inside" not in plan["text"]


CLI = os.environ.get("TETPROBE_CLI", "")
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "samples", "scenes")


@pytest.mark.skipif(not (CLI and os.path.exists(CLI)), reason="TETPROBE_CLI is not set")
def test_cli_place_writes_probes_and_curve(tmp_path):
    out, curve = tmp_path / "probes.csv", tmp_path / "curve.json"
    result = subprocess.run([CLI, "place", os.path.join(SCENES, "two_rooms.json"), "-o", str(out), "--target", "60",
                             "--spacing", "0.75", "--rays", "32", "--curve", str(curve)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    rows = np.loadtxt(out, delimiter=",", ndmin=2)
    assert rows.shape == (60, 3)
    points = json.loads(curve.read_text())["error_curve"]
    assert points[-1]["probes"] == 60 and points[0]["probes"] < 60 and points[0]["error"] > points[-1]["error"]
    # The two rooms' shared wall (x in 4..4.2) holds no probe.
    assert not ((rows[:, 0] > 4.0) & (rows[:, 0] < 4.2)).any()
    bad = subprocess.run([CLI, "place", os.path.join(SCENES, "two_rooms.json"), "-o", str(tmp_path / "bad.csv"),
                          "--spacing", "0"], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 1 and "spacing" in bad.stderr
    assert not (tmp_path / "bad.csv").exists()


def test_cancelled_placement_writes_nothing():
    """Through the raw C ABI: a cancel returns TP_ERROR_CANCELLED and leaves the caller's buffers as they were."""
    import ctypes
    from tetprobe import _native
    scene = room_scene()
    options = _native.PlacementOptions()
    _native.check(_native.lib.tp_placement_options_init(ctypes.byref(options)))
    options.spacing, options.target_count, options.error_bound = 0.75, 40, 0
    options.progress = _native.ProgressFn(lambda user, fraction, stage: 1 if stage == b"select" else 0)
    bound = ctypes.c_size_t()
    _native.check(_native.lib.tp_place_probes_bound(scene._live(), ctypes.byref(options), ctypes.byref(bound)))
    assert bound.value == 256
    positions = np.full((bound.value, 3), 7.0, np.float32)
    curve = np.full((bound.value + 1, 2), 7.0, np.float32)
    count, points = ctypes.c_size_t(5), ctypes.c_size_t(5)
    status = _native.lib.tp_place_probes(scene._live(), ctypes.byref(options), positions, bound.value,
                                         ctypes.byref(count), curve, bound.value + 1, ctypes.byref(points))
    assert status == Status.CANCELLED
    assert count.value == 0 and points.value == 0
    assert (positions == 7).all() and (curve == 7).all()
    # Too small a buffer: the counts are reported and nothing is written.
    options.progress = _native.ProgressFn()
    status = _native.lib.tp_place_probes(scene._live(), ctypes.byref(options), positions, 39, ctypes.byref(count),
                                         curve, bound.value + 1, ctypes.byref(points))
    assert status == Status.BUFFER_TOO_SMALL and count.value == 40
    assert (positions == 7).all()
