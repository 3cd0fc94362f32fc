"""Store: build, queries against scipy's Delaunay interpolation, exactness, round trips, errors, layouts."""
import re
import struct

import numpy as np
import pytest
from scipy.interpolate import LinearNDInterpolator
from scipy.spatial import Delaunay

import tetprobe
from tetprobe import Error, Status, Store


def half(values):
    """What the store keeps of SH: IEEE half precision."""
    return np.asarray(values, dtype=np.float32).astype(np.float16).astype(np.float32)


def random_set(n, seed, offset=0.0, scale=1.0):
    rng = np.random.default_rng(seed)
    positions = (rng.random((n, 3)) * scale + offset).astype(np.float32)
    sh = rng.uniform(-1.0, 1.0, (n, 27)).astype(np.float32)
    return positions, sh


def linear_sh(points):
    points = np.asarray(points, dtype=np.float64)
    k = np.arange(27)
    return (0.5 + 0.1 * (k % 7) + np.outer(points[:, 0], 0.3 * ((k % 3) - 1)) +
            np.outer(points[:, 1], 0.2 * ((k % 5) - 2)) - np.outer(points[:, 2], 0.1 * ((k % 4) - 1.5)))


def inside_points(tri, m, seed, low=0.0, high=1.0):
    rng = np.random.default_rng(seed)
    points = rng.uniform(low, high, (4 * m, 3)).astype(np.float32)
    return points[tri.find_simplex(points.astype(np.float64)) >= 0][:m]


@pytest.mark.parametrize("seed,offset", [(1, 0.0), (2, 0.0), (3, 1000.0)])
def test_agrees_with_scipy_delaunay_interpolation(seed, offset):
    positions, sh = random_set(300, seed, offset=offset, scale=10.0)
    store = Store.build(positions, sh)
    tri = Delaunay(positions.astype(np.float64))
    reference = LinearNDInterpolator(tri, half(sh).astype(np.float64))
    points = inside_points(tri, 2000, seed + 100, offset + 0.5, offset + 9.5)
    assert len(points) > 500
    ours, hints = store.interpolate(points)
    expected = reference(points.astype(np.float64))
    # Relative to the field's magnitude (1): float barycentrics in a local frame.
    assert np.max(np.abs(ours - expected)) < 2e-3
    assert np.all(hints >= 0)


def test_weights_agree_with_scipy_barycentrics():
    positions, sh = random_set(200, 7)
    store = Store.build(positions, sh)
    tri = Delaunay(positions.astype(np.float64))
    points = inside_points(tri, 500, 8)
    indices, weights, hints = store.weights(points)
    assert indices.shape == (len(points), 4) and weights.shape == (len(points), 4) and hints.dtype == np.int32
    simplices = tri.find_simplex(points.astype(np.float64))
    transform = tri.transform[simplices]
    bary = np.einsum("nij,nj->ni", transform[:, :3, :], points - transform[:, 3, :])
    bary = np.hstack([bary, 1 - bary.sum(axis=1, keepdims=True)])
    for row in range(len(points)):
        ours = {int(i): 0.0 for i in indices[row]}
        for i, w in zip(indices[row], weights[row]):
            ours[int(i)] += float(w)
        theirs = dict(zip(tri.simplices[simplices[row]].tolist(), bary[row].tolist()))
        for probe in set(ours) | set(theirs):
            assert abs(ours.get(probe, 0.0) - theirs.get(probe, 0.0)) < 1e-4


def test_exact_at_every_probe_and_weights_are_a_partition_of_unity():
    positions, sh = random_set(150, 11)
    store = Store.build(positions, sh)
    out, _ = store.interpolate(positions)
    assert np.max(np.abs(out - half(sh))) < 1e-4  # float barycentrics in slivers
    indices, weights, _ = store.weights(positions)
    for row in range(len(positions)):
        hit = (indices[row] == row) & (np.abs(weights[row] - 1.0) < 1e-4)
        assert hit.sum() == 1
    for i in (0, 17, 149):
        assert np.array_equal(store.probe_sh(i), half(sh[i]))
    rng = np.random.default_rng(12)
    _, weights, _ = store.weights(rng.uniform(0.2, 0.8, (300, 3)))
    assert np.all(weights >= -1e-6) and np.all(weights <= 1 + 1e-6)
    assert np.max(np.abs(weights.sum(axis=1) - 1.0)) < 1e-5


def test_linear_field_is_reproduced_inside_the_hull():
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float32)
    rng = np.random.default_rng(5)
    positions = np.vstack([corners, rng.random((120, 3)).astype(np.float32)])
    store = Store.build(positions, linear_sh(positions))
    points = rng.uniform(0.01, 0.99, (1000, 3)).astype(np.float32)
    out, _ = store.interpolate(points)
    expected = linear_sh(points)
    assert np.max(np.abs(out - expected) / (np.abs(expected) + 0.05)) < 2e-3


def test_hints_follow_a_moving_object_and_give_the_same_answer():
    positions, sh = random_set(400, 21)
    store = Store.build(positions, sh)
    path = np.stack([np.linspace(0.2, 0.8, 300), 0.5 + 0.1 * np.sin(np.linspace(0, 6, 300)),
                     np.full(300, 0.4)], axis=1).astype(np.float32)
    hint, steps, values = -1, [], []
    for p in path:
        location = store.locate(p, hint)
        hint = location["hint"]
        assert hint == location["cell"]
        steps.append(location["steps"])
        value, new_hint = store.interpolate(p, None)
        values.append(value)
    assert np.mean(steps[1:]) < 3.0
    batch, hints = store.interpolate(path)
    assert np.array_equal(batch, np.array(values))
    again, hints2 = store.interpolate(path, hints)
    assert np.array_equal(again, batch) and np.array_equal(hints2, hints)


def test_strided_views_equal_packed_arrays():
    positions, sh = random_set(100, 31)
    store = Store.build(positions, sh)
    rng = np.random.default_rng(32)
    wide = rng.uniform(-0.5, 1.5, (200, 5)).astype(np.float32)  # points in columns 1..3, row stride 20 bytes
    view = wide[:, 1:4]
    assert not view.flags["C_CONTIGUOUS"]
    packed = np.ascontiguousarray(view)
    a, ha = store.interpolate(view)
    b, hb = store.interpolate(packed)
    assert np.array_equal(a, b) and np.array_equal(ha, hb)
    ia, wa, _ = store.weights(view)
    ib, wb, _ = store.weights(packed)
    assert np.array_equal(ia, ib) and np.array_equal(wa, wb)
    c, _ = store.interpolate(packed.astype(np.float64))
    assert np.array_equal(a, c)
    d, _ = store.interpolate(packed[::-1])
    assert np.array_equal(d, a[::-1])
    # Build from strided views too.
    big = np.zeros((100, 4), dtype=np.float32)
    big[:, :3] = positions
    sh_wide = np.zeros((100, 30), dtype=np.float32)
    sh_wide[:, :27] = sh
    again = Store.build(big[:, :3], sh_wide[:, :27])
    assert again.to_bytes() == store.to_bytes()


def test_single_point_and_empty_batches():
    positions, sh = random_set(50, 41)
    store = Store.build(positions, sh)
    value, hint = store.interpolate(positions[3])
    assert value.shape == (27,) and isinstance(hint, int) and hint >= 0
    probes, weights, hint = store.weights(positions[3])
    assert probes.shape == (4,) and weights.shape == (4,)
    out, hints = store.interpolate(np.zeros((0, 3), dtype=np.float32))
    assert out.shape == (0, 27) and hints.shape == (0,)


def test_outside_the_hull_extrapolates_or_raises_without_outer_cells():
    positions, sh = random_set(80, 51)
    store = Store.build(positions, sh)
    far = np.array([[5.0, 0.5, 0.5], [1e9, -1e9, 1e9], [-3.0, -3.0, -3.0]], dtype=np.float32)
    out, _ = store.interpolate(far)
    assert np.all(np.isfinite(out))
    assert store.locate(far[0])["kind"] == "outer"
    # Values stay within the probes' range (weights are a partition of unity on the hull).
    assert out.max() <= half(sh).max() + 1e-4 and out.min() >= half(sh).min() - 1e-4
    closed = Store.build(positions, sh, extrapolate=False)
    assert closed.info()["outer_cells"] == 0 and not closed.info()["extrapolation"]
    with pytest.raises(Error) as raised:
        closed.interpolate(far[:1])
    assert raised.value.status == Status.OUTSIDE


def test_info_counts_and_merged_duplicates():
    positions, sh = random_set(60, 61)
    duplicated = np.vstack([positions, positions[:5]])
    store = Store.build(duplicated, np.vstack([sh, sh[:5]]))
    info = store.info()
    for key in ("probes", "cells", "inner_cells", "outer_cells", "merged_probes", "index_bits", "bytes",
                "dimension", "input_probes"):
        assert key in info
    assert info["probes"] == 60 and info["input_probes"] == 65 and info["merged_probes"] == 5
    assert info["cells"] == info["inner_cells"] + info["outer_cells"]
    assert info["index_bits"] == 16 and info["dimension"] == 3
    assert info["bytes"] == len(store.to_bytes())
    assert np.array_equal(store.probe_sh(62), store.probe_sh(2))
    wide = Store.build(positions, sh, index32=True)
    assert wide.info()["index_bits"] == 32
    assert np.array_equal(wide.interpolate(positions)[0], Store.build(positions, sh).interpolate(positions)[0])


def test_small_and_flat_sets():
    one = Store.build([[1.0, 2.0, 3.0]], np.ones((1, 27)))
    assert one.info()["dimension"] == 0
    value, _ = one.interpolate([100.0, -5.0, 0.0])
    assert np.allclose(value, 1.0)
    line = Store.build([[0, 0, 0], [2, 0, 0]], np.stack([np.zeros(27), np.full(27, 2.0)]))
    assert line.info()["dimension"] == 1
    assert np.allclose(line.interpolate([0.5, 0.0, 0.0])[0], 0.5, atol=1e-3)
    rng = np.random.default_rng(71)
    flat = np.column_stack([rng.random((40, 2)), np.zeros(40)]).astype(np.float32)
    store = Store.build(flat, linear_sh(flat))
    assert store.info()["dimension"] == 2
    tri = Delaunay(flat[:, :2].astype(np.float64))
    points = np.column_stack([rng.uniform(0.1, 0.9, (300, 2)), np.zeros(300)]).astype(np.float32)
    points = points[tri.find_simplex(points[:, :2].astype(np.float64)) >= 0]
    out, _ = store.interpolate(points)
    expected = linear_sh(points)
    assert np.max(np.abs(out - expected) / (np.abs(expected) + 0.05)) < 2e-3


def test_save_load_round_trip(tmp_path):
    positions, sh = random_set(120, 81)
    store = Store.build(positions, sh)
    blob = store.to_bytes()
    path = tmp_path / "probes.tpb"
    store.save(path)
    assert path.read_bytes() == blob
    assert [p.name for p in tmp_path.iterdir()] == ["probes.tpb"]  # no temporary left behind
    from_file = Store.load(str(path))
    from_bytes = Store.load(blob)
    from_array = Store.load(bytearray(blob))
    points = np.random.default_rng(82).random((100, 3)).astype(np.float32)
    expected, _ = store.interpolate(points)
    for loaded in (from_file, from_bytes, from_array):
        assert loaded.to_bytes() == blob
        assert np.array_equal(loaded.interpolate(points)[0], expected)
    assert Store.load(path).info() == store.info()


def test_files_only_regular_ones_within_the_cap_load(tmp_path):
    store = Store.build(*random_set(40, 83))
    blob = store.to_bytes()
    path = tmp_path / "probes.tpb"
    store.save(path)
    for source, words in (("/dev/zero", "character device"), (tmp_path, "a directory")):
        with pytest.raises(Error) as raised:
            Store.load(source)
        assert raised.value.status == Status.IO and words in raised.value.message
    with pytest.raises(Error) as raised:
        Store.load(path, max_file_bytes=len(blob) - 1)
    assert raised.value.status == Status.IO and "above the load cap of %d bytes" % (len(blob) - 1) in raised.value.message
    assert Store.load(path, max_file_bytes=len(blob)).to_bytes() == blob


def test_save_keeps_the_mode_writes_through_links_and_cleans_stale_temporaries(tmp_path):
    import os
    import subprocess
    store = Store.build(*random_set(40, 84))
    blob = store.to_bytes()
    target = tmp_path / "target.tpb"
    target.write_bytes(b"old")
    os.chmod(target, 0o600)
    link = tmp_path / "link.tpb"
    link.symlink_to("target.tpb")
    # A killed save's temporary file (its process is gone) and a live one's (this process's parent).
    gone = subprocess.Popen(["true"])
    gone.wait()
    stale = tmp_path / ("target.tpb.tetprobe-tmp-%d-0123456789abcdef" % gone.pid)
    live = tmp_path / ("target.tpb.tetprobe-tmp-%d-0123456789abcdef" % os.getppid())
    stale.write_bytes(b"partial")
    live.write_bytes(b"being written")
    store.save(link)
    assert link.is_symlink() and target.read_bytes() == blob
    assert (target.stat().st_mode & 0o7777) == 0o600
    assert not stale.exists() and live.exists()


def test_bad_input_raises_clear_errors(tmp_path):
    positions, sh = random_set(20, 91)
    with pytest.raises(Error) as raised:
        Store.build(np.zeros((0, 3), dtype=np.float32))
    assert raised.value.status == Status.DEGENERATE and raised.value.message
    bad = positions.copy()
    bad[3, 1] = np.nan
    with pytest.raises(Error) as raised:
        Store.build(bad, sh)
    assert raised.value.status == Status.INVALID_ARGUMENT
    bad[3, 1] = np.inf
    with pytest.raises(Error):
        Store.build(bad, sh)
    with pytest.raises(ValueError, match="sh has 10 rows"):
        Store.build(positions, sh[:10])
    with pytest.raises(ValueError):
        Store.build(positions[:, :2])
    with pytest.raises(ValueError):
        Store.build(positions, sh[:, :9])
    store = Store.build(positions, sh)
    with pytest.raises(Error) as raised:
        store.interpolate([[0.5, np.nan, 0.5]])
    assert raised.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(ValueError):
        store.interpolate(positions, hints=[-1, -1])
    with pytest.raises(Error) as raised:
        store.probe_sh(20)
    assert raised.value.status == Status.INVALID_ARGUMENT
    with pytest.raises(Error) as raised:
        Store.load(str(tmp_path / "missing.tpb"))
    assert raised.value.status == Status.IO and raised.value.message
    with pytest.raises(Error) as raised:
        store.save(tmp_path / "no-such-dir" / "x.tpb")
    assert raised.value.status == Status.IO
    blob = store.to_bytes()
    for cut in (0, 1, 50, len(blob) // 2, len(blob) - 1):
        with pytest.raises(Error) as raised:
            Store.load(blob[:cut])
        assert raised.value.status == Status.INVALID_BLOB
    corrupt = bytearray(blob)
    corrupt[len(blob) // 2] ^= 0xFF
    with pytest.raises(Error) as raised:
        Store.load(bytes(corrupt))
    assert raised.value.status == Status.INVALID_BLOB
    store.close()
    with pytest.raises(Error):
        store.info()
    store.close()  # twice is fine


def test_progress_can_cancel_and_exceptions_propagate():
    positions, sh = random_set(200, 101)
    seen = []
    Store.build(positions, sh, progress=lambda fraction, stage: seen.append((fraction, stage)))
    assert seen and all(0.0 <= f <= 1.0 for f, _ in seen)
    with pytest.raises(Error) as raised:
        Store.build(positions, sh, progress=lambda fraction, stage: True)
    assert raised.value.status == Status.CANCELLED

    def broken(fraction, stage):
        raise KeyError("from the callback")

    with pytest.raises(KeyError):
        Store.build(positions, sh, progress=broken)


def test_context_manager_and_repr():
    positions, sh = random_set(30, 111)
    with Store.build(positions, sh) as store:
        assert "30 probes" in repr(store)
    assert "closed" in repr(store)
    assert isinstance(tetprobe.Error(1, "x"), RuntimeError)


# ---- format 4: layouts, batch options, version

def dense_weights(indices, weights, probes):
    """Per-query weights as a dense [M, probes] matrix (slot order and repeated unused slots drop out)."""
    dense = np.zeros((indices.shape[0], probes), dtype=np.float64)
    np.add.at(dense, (np.repeat(np.arange(indices.shape[0]), 4), indices.reshape(-1)), weights.reshape(-1))
    return dense


def mixed_points(m, seed, low=-0.5, high=1.5):
    """Random points in a box around the unit cube: some inside the probes' hull, many outside."""
    return np.random.default_rng(seed).uniform(low, high, (m, 3)).astype(np.float32)


@pytest.mark.parametrize("index32", [False, True])
def test_compact_layout_answers_like_the_fast_layout(index32):
    positions, sh = random_set(500, 201)
    fast = Store.build(positions, sh, index32=index32)
    compact = Store.build(positions, sh, compact=True, index32=index32)
    fast_info, compact_info = fast.info(), compact.info()
    assert not fast_info["compact"] and compact_info["compact"]
    assert compact_info["flags"] & tetprobe._native.BUILD_COMPACT
    assert not fast_info["flags"] & tetprobe._native.BUILD_COMPACT
    assert fast_info["format_version"] == 6 and compact_info["format_version"] == 6
    assert fast_info["layout"] == "fast" and compact_info["layout"] == "compact"
    assert compact_info["bytes"] < fast_info["bytes"]
    for key in ("probes", "cells", "inner_cells", "outer_cells", "index_bits"):
        assert compact_info[key] == fast_info[key], key
    points = mixed_points(4000, 202, -0.3, 1.3)
    tri = Delaunay(positions.astype(np.float64))
    inside = tri.find_simplex(points.astype(np.float64)) >= 0
    assert 500 < inside.sum() < len(points) - 500  # both inside and outside the hull
    fast_indices, fast_weights, fast_cells = fast.weights(points)
    compact_indices, compact_weights, compact_cells = compact.weights(points)
    assert np.array_equal(fast_cells, compact_cells)
    assert np.max(np.abs(dense_weights(fast_indices, fast_weights, 500) -
                         dense_weights(compact_indices, compact_weights, 500))) <= 1e-6
    fast_sh, _ = fast.interpolate(points)
    compact_sh, _ = compact.interpolate(points)
    assert np.max(np.abs(fast_sh - compact_sh)) <= 1e-5
    # The compact blob round-trips and stays compact (neighbours rebuilt on load answer the same).
    again = Store.load(compact.to_bytes())
    assert again.info()["compact"] and again.to_bytes() == compact.to_bytes()
    _, again_weights, again_cells = again.weights(points, fast_cells)
    assert np.array_equal(again_cells, fast_cells)
    assert np.array_equal(again_weights, compact_weights)
    # The rebuilt layout keeps no cells: loaded from its bytes it answers as compact, bit for bit.
    rebuilt = Store.build(positions, sh, layout="rebuilt")
    info = rebuilt.info()
    assert info["layout"] == "rebuilt" and info["section_bytes"]["cells"] == 0 and info["section_bytes"]["grid"] == 0
    assert info["cells"] == compact.info()["cells"] and info["bytes"] < compact.info()["bytes"]
    reloaded = Store.load(rebuilt.to_bytes())
    rebuilt_indices, rebuilt_weights, rebuilt_cells = reloaded.weights(points)
    assert np.array_equal(rebuilt_cells, compact_cells) and np.array_equal(rebuilt_indices, compact_indices)
    assert np.array_equal(rebuilt_weights, compact_weights)
    assert np.array_equal(reloaded.interpolate(points)[0], compact_sh)
    assert Store.build(positions, sh, layout="compact").info()["layout"] == "compact"
    with pytest.raises(ValueError, match="layout"):
        Store.build(positions, sh, compact=True, layout="rebuilt")
    with pytest.raises(ValueError, match="layout"):
        Store.build(positions, sh, layout="tiny")


def test_threads_give_the_same_answers_as_one_thread():
    positions, sh = random_set(300, 211)
    store = Store.build(positions, sh)
    points = mixed_points(12000, 212)  # enough for the library to split the batch over 2 threads
    one, one_cells = store.interpolate(points, threads=1)
    two, two_cells = store.interpolate(points, threads=2)
    assert np.array_equal(one, two) and np.array_equal(one_cells, two_cells)
    indices1, weights1, cells1 = store.weights(points, threads=1)
    indices2, weights2, cells2 = store.weights(points, threads=2)
    assert np.array_equal(indices1, indices2) and np.array_equal(weights1, weights2)
    assert np.array_equal(cells1, one_cells) and np.array_equal(cells2, one_cells)
    zero, _ = store.interpolate(points, threads=0)  # 0 = the calling thread
    assert np.array_equal(zero, one)
    # With hints given, every thread reads and updates its own range of them.
    hinted, hinted_cells = store.interpolate(points, one_cells, threads=2)
    assert np.array_equal(hinted, one) and np.array_equal(hinted_cells, one_cells)
    with pytest.raises(ValueError):
        store.interpolate(points, threads=-1)


def test_chained_hints_give_the_same_answers_as_cold_starts():
    positions, sh = random_set(400, 221)
    store = Store.build(positions, sh)
    # A spatially coherent path (the case chaining is for) and scattered points, inside and outside.
    t = np.linspace(0.0, 1.0, 3000)
    path = np.stack([-0.3 + 1.6 * t, 0.5 + 0.3 * np.sin(9 * t), 0.5 + 0.6 * np.cos(5 * t)], axis=1).astype(np.float32)
    for points in (path, mixed_points(3000, 222)):
        inner = np.array([store.locate(p)["kind"] == "inner" for p in points])
        assert 300 < inner.sum() < len(points) - 300
        cold, cold_cells = store.interpolate(points)
        indices, weights, _ = store.weights(points)
        for threads in (1, 2):
            repeat = 1 if threads == 1 else 4  # 12,000 queries: split over 2 threads
            chained, chained_cells = store.interpolate(np.tile(points, (repeat, 1)), chain_hints=True, threads=threads)
            assert chained_cells is None  # no hint buffer: the library reports no cells
            chained_indices, chained_weights, _ = store.weights(np.tile(points, (repeat, 1)), chain_hints=True,
                                                                threads=threads)
            for r in range(repeat):
                rows_ = slice(r * len(points), (r + 1) * len(points))
                # Inside the hull the cell holding a point is decided exactly: the same bytes from any start.
                assert np.array_equal(chained[rows_][inner], cold[inner])
                assert np.array_equal(chained_indices[rows_][inner], indices[inner])
                assert np.array_equal(chained_weights[rows_][inner], weights[inner])
                # Outer cells accept a point within a weight tolerance, so near the face two of them share
                # the start decides which answers; the answer is continuous across that face.
                assert np.max(np.abs(chained[rows_] - cold)) <= 1e-4
                assert np.max(np.abs(dense_weights(chained_indices[rows_], chained_weights[rows_], 400) -
                                     dense_weights(indices, weights, 400))) <= 5e-5
    value, hint = store.interpolate(path[0], chain_hints=True)
    assert hint is None and np.allclose(value, store.interpolate(path[0])[0], atol=1e-4)
    with pytest.raises(ValueError):
        store.interpolate(path, hints=np.full(len(path), -1), chain_hints=True)


def test_outside_batch_names_the_first_outside_query():
    positions, sh = random_set(80, 231)
    closed = Store.build(positions, sh, extrapolate=False)
    tri = Delaunay(positions.astype(np.float64))
    points = inside_points(tri, 60, 233, 0.2, 0.8)
    assert len(points) == 60
    points[37] = (3.0, 0.5, 0.5)
    points[52] = (0.5, -4.0, 0.5)
    for call in (closed.interpolate, closed.weights):
        for threads in (1, 2):
            with pytest.raises(Error) as raised:
                call(points, threads=threads)
            assert raised.value.status == Status.OUTSIDE
            assert re.search(r"\b37\b", raised.value.message), raised.value.message


def test_older_format_blobs_are_refused_with_a_version_error():
    positions, sh = random_set(50, 241)
    for compact in (False, True):
        blob = bytearray(Store.build(positions, sh, compact=compact).to_bytes())
        assert struct.unpack_from("<I", blob, 8)[0] == 6
        for version in (5, 4, 3, 2, 1, 7, 99):
            old = bytearray(blob)
            struct.pack_into("<I", old, 8, version)  # nothing else fixed: not even the checksum
            with pytest.raises(Error) as raised:
                Store.load(bytes(old))
            assert raised.value.status == Status.VERSION
            assert "rebuild" in raised.value.message.lower()
            assert str(version) in raised.value.message


def test_info_flags_are_the_blobs_build_flags():
    positions, sh = random_set(40, 251)
    info = Store.build(positions, sh).info()
    assert info["flags"] == 0 and not info["compact"] and info["extrapolation"]
    closed = Store.build(positions, sh, compact=True, extrapolate=False, index32=True).info()
    assert closed["flags"] == (tetprobe._native.BUILD_COMPACT | tetprobe._native.BUILD_NO_EXTRAPOLATION |
                               tetprobe._native.BUILD_INDEX32)


# The 8-bit codes' step and the larger end of the ratio range per coefficient (capi/tetprobe.h,
# docs/store_format.md): coefficient i of a non-negative radiance decodes within c0 (step / 2 + max / 1024).
UNORM8_STEP = np.array([0, *[np.sqrt(3) / 127] * 3, *[np.sqrt(15) / 2 / 127] * 2, np.sqrt(5) / 170,
                        *[np.sqrt(15) / 2 / 127] * 2])
UNORM8_MAX = np.array([0, *[np.sqrt(3)] * 3, *[np.sqrt(15) / 2] * 2, np.sqrt(5), *[np.sqrt(15) / 2] * 2])
RECORD_BYTES = {"half": 64, "unorm8": 32, "half_l1": 32, "unorm8_l1": 16}  # fast layout, per probe


def radiance_sh(n, seed):
    """SH of non-negative radiance: per channel L0 in [0.5, 2], every other coefficient L0 times a ratio
    inside half its range."""
    rng = np.random.default_rng(seed)
    sh = np.zeros((n, 27), np.float32)
    for c in range(3):
        l0 = rng.uniform(0.5, 2.0, n)
        sh[:, 9 * c] = l0
        for i in range(1, 9):
            sh[:, 9 * c + i] = l0 * rng.uniform(-0.5, 0.5, n) * UNORM8_MAX[i]
    return sh


@pytest.mark.parametrize("encoding", ["half", "unorm8", "half_l1", "unorm8_l1"])
@pytest.mark.parametrize("quantize", [False, True])
def test_sh_encodings_and_quantized_positions(encoding, quantize):
    positions, _ = random_set(300, 261)
    sh = radiance_sh(300, 262)
    store = Store.build(positions, sh, sh_encoding=encoding, quantize_positions=quantize)
    info = store.info()
    assert info["format_version"] == 6 and info["layout"] == "fast"
    assert info["sh_encoding"] == encoding and info["quantized_positions"] == quantize
    sections = info["section_bytes"]
    assert list(sections) == list(tetprobe._native.STORE_SECTIONS)
    assert sum(sections.values()) == info["bytes"] == len(store.to_bytes())
    assert sections["sh"] == 300 * RECORD_BYTES[encoding]
    assert sections["positions"] == 300 * (6 if quantize else 12)
    assert sections["normals"] == info["hull_probes"] * (4 if quantize else 12) and info["hull_probes"] > 0
    assert sections["input_remap"] == 0 and sections["probe_source"] == 300 * 2
    step = np.array(info["position_step"])
    if quantize:
        # A power of two spanning each axis's extent in at most 65,534 steps, less than twice that.
        extent = positions.max(axis=0).astype(np.float64) - positions.min(axis=0)
        assert np.all(np.frexp(step)[0] == 0.5)
        assert np.all((step >= extent / 65534) & (step < 2 * extent / 65534))
    else:
        assert np.all(step == 0)

    # Each probe reads its decoded SH: within the encoding's bound of the input, band 2 zero for L1.
    decoded = np.array([store.probe_sh(i) for i in range(300)])
    l1 = encoding.endswith("_l1")
    for k in range(27):
        i, l0 = k % 9, sh[:, k - k % 9].astype(np.float64)
        if l1 and i >= 4:
            assert np.all(decoded[:, k] == 0)
        elif encoding.startswith("half") or i == 0:
            assert np.array_equal(decoded[:, k], half(sh[:, k]))
        else:
            assert np.all(np.abs(decoded[:, k] - sh[:, k]) <= l0 * (UNORM8_STEP[i] / 2 + UNORM8_MAX[i] / 1024))

    # Float positions: a query at a probe returns its decoded SH exactly. Quantised ones moved the probes
    # by at most half a step (1e-5 here): at the inputs the answers barely change (more only in slivers).
    out, _ = store.interpolate(positions)
    if not quantize:
        assert np.array_equal(out, decoded)
    else:
        exact = Store.build(positions, sh, sh_encoding=encoding)
        assert np.median(np.abs(out - exact.interpolate(positions)[0])) < 1e-4
    assert Store.load(store.to_bytes()).to_bytes() == store.to_bytes()


def test_bad_sh_encoding_is_refused():
    positions, sh = random_set(20, 263)
    with pytest.raises(ValueError, match="sh_encoding"):
        Store.build(positions, sh, sh_encoding="float8")
