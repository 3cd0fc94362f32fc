"""Store.sample_volume: each point is the single query replayed in the documented walk with the carried hint (bit
for bit; tetrahedra, flat, line, leak-free and bounded stores), the L1 and Unity formats are the documented
repackings, strided views (a Light Probe Proxy Volume atlas) leave other bytes alone, bad arguments are refused."""
import math

import numpy as np
import pytest

from tetprobe import Error, Status, Store


def walk(dims):
    """The header's walk order: slices ascending, rows alternating per slice, points alternating per row walked."""
    nx, ny, nz = dims
    row = 0
    for z in range(nz):
        for j in range(ny):
            y = ny - 1 - j if z % 2 else j
            for i in range(nx):
                yield (nx - 1 - i if row % 2 else i), y, z
            row += 1


def replay(store, origin, cell, dims, hint=-1):
    """Single queries in the walk with one carried hint -> (sh[nz, ny, nx, 27], cell of point (0, 0, 0))."""
    nx, ny, nz = dims
    out = np.full((nz, ny, nx, 27), np.nan, dtype=np.float32)
    first = None
    for x, y, z in walk(dims):
        point = np.array([np.float64(origin[a]) + np.float64([x, y, z][a]) * np.float64(cell[a]) for a in range(3)],
                         dtype=np.float32)
        out[z, y, x], hint = store.interpolate(point, hints=hint)
        if first is None:
            first = hint
    return out, first


def unity_constants(sh):
    """The header's Unity constants of sh[..., 27] -> [..., 7, 4], in float32 as documented."""
    sp = math.sqrt(math.pi)
    s = np.array([1 / (2 * sp)] + [math.sqrt(3) / (3 * sp)] * 3 + [math.sqrt(15) / (8 * sp)] * 2 +
                 [math.sqrt(5) / (16 * sp), math.sqrt(15) / (8 * sp), math.sqrt(15) / (16 * sp)]).astype(np.float32)
    u = sh.reshape(sh.shape[:-1] + (3, 9)) * s  # float32 products
    out = np.empty(sh.shape[:-1] + (7, 4), dtype=np.float32)
    for c in range(3):
        out[..., c, :] = np.stack([u[..., c, 3], u[..., c, 1], u[..., c, 2], u[..., c, 0] - u[..., c, 6]], axis=-1)
        out[..., 3 + c, :] = np.stack([u[..., c, 4], u[..., c, 5], np.float32(3) * u[..., c, 6], u[..., c, 7]], axis=-1)
    out[..., 6, :3] = u[..., :, 8]
    out[..., 6, 3] = 1
    return out


def cloud(n=120, seed=3, flags=None):
    rng = np.random.default_rng(seed)
    positions = rng.uniform(-1, 1, (n, 3)).astype(np.float32)
    sh = rng.uniform(-1, 1, (n, 27)).astype(np.float32)
    return Store.build(positions, sh, **(flags or {}))


ORIGIN = np.array([-1.3, -1.2, -1.45], dtype=np.float32)
CELL = np.array([0.31, 0.27, 0.4], dtype=np.float32)
DIMS = (9, 10, 8)


def test_each_point_is_the_single_query_in_the_walk_bit_for_bit():
    store = cloud()
    expected, first = replay(store, ORIGIN, CELL, DIMS)
    hint = np.full(1, -1, dtype=np.int32)
    got = store.sample_volume(ORIGIN, CELL, DIMS, hint=hint)
    assert got.shape == (8, 10, 9, 27) and got.dtype == np.float32
    assert got.tobytes() == expected.tobytes()
    assert hint[0] == first
    # The next frame starts from that cell: the same bits.
    assert store.sample_volume(ORIGIN, CELL, DIMS, hint=int(hint[0])).tobytes() == expected.tobytes()
    # Random probes put no grid point on a facet: there the answer does not depend on the hint at all, and the
    # volume is also bit for bit the cold batch query at its points.
    nx, ny, nz = DIMS
    z, y, x = np.meshgrid(range(nz), range(ny), range(nx), indexing="ij")
    points = np.stack([(np.float64(ORIGIN[a]) + np.float64(CELL[a]) * (x, y, z)[a]).astype(np.float32)
                       for a in range(3)], axis=-1).reshape(-1, 3)
    cold, _ = store.interpolate(points)
    assert cold.reshape(got.shape).tobytes() == got.tobytes()


@pytest.mark.parametrize("kind", ["flat", "line", "point", "lattice"])
def test_flat_line_point_and_lattice_stores(kind):
    rng = np.random.default_rng(8)
    if kind == "flat":
        positions = np.column_stack([rng.uniform(-1, 1, 30), np.full(30, 0.2), rng.uniform(-1, 1, 30)])
    elif kind == "line":
        positions = np.column_stack([np.linspace(-1, 1, 9), np.full(9, 0.5), np.full(9, -0.3)])
    elif kind == "point":
        positions = np.array([[0.1, 0.2, 0.3]])
    else:  # grid points on the probes' facets and at probes: ties the carried hint decides
        g = np.arange(4, dtype=np.float32) - 1.5
        positions = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
    positions = positions.astype(np.float32)
    store = Store.build(positions, rng.uniform(-1, 1, (len(positions), 27)).astype(np.float32))
    origin, cell, dims = (np.float32([-2, -2, -2]), np.float32([0.5, 0.5, 0.5]), (9, 9, 9))
    expected, _ = replay(store, origin, cell, dims)
    assert store.sample_volume(origin, cell, dims).tobytes() == expected.tobytes()


def test_outside_a_bounded_store_names_the_first_point_and_fills_the_rest():
    store = cloud(flags={"extrapolate": False})
    with pytest.raises(Error) as raised:
        store.sample_volume(ORIGIN, CELL, DIMS)
    assert raised.value.status == Status.OUTSIDE
    assert "(0, 0, 0)" in str(raised.value)
    inside = store.sample_volume(ORIGIN * 0.1, CELL * 0.1, (4, 4, 4))
    expected, _ = replay(store, ORIGIN * 0.1, CELL * 0.1, (4, 4, 4))
    assert inside.tobytes() == expected.tobytes()


def test_l1_and_unity_formats_repack_the_l2_volume():
    store = cloud()
    l2 = store.sample_volume(ORIGIN, CELL, DIMS)
    l1 = store.sample_volume(ORIGIN, CELL, DIMS, bands=1)
    assert l1.shape == (8, 10, 9, 12)
    assert l1.tobytes() == l2.reshape(8, 10, 9, 3, 9)[..., :4].reshape(8, 10, 9, 12).tobytes()
    u2 = store.sample_volume(ORIGIN, CELL, DIMS, unity=True)
    assert u2.shape == (8, 10, 9, 7, 4)
    assert u2.tobytes() == unity_constants(l2).tobytes()
    u1 = store.sample_volume(ORIGIN, CELL, DIMS, bands=1, unity=True)
    l1_only = l2.reshape(8, 10, 9, 3, 9).copy()
    l1_only[..., 4:] = 0
    assert u1.tobytes() == unity_constants(l1_only.reshape(8, 10, 9, 27))[..., :3, :].tobytes()
    # ShadeSH9 of the L2 constants is the irradiance over pi (tetprobe.sh's evaluation).
    from tetprobe import sh as shmod
    n = np.array([0.48, -0.6, 0.64], dtype=np.float32)
    c = u2[3, 4, 5]
    shade = np.array([c[k, :3] @ n + c[k, 3] + c[3 + k] @ np.array([n[0] * n[1], n[1] * n[2], n[2] * n[2], n[2] * n[0]]) +
                      c[6, k] * (n[0] ** 2 - n[1] ** 2) for k in range(3)])
    np.testing.assert_allclose(shade * math.pi, shmod.eval_irradiance(l2[3, 4, 5], n), rtol=1e-5, atol=1e-6)


def test_a_strided_view_into_a_proxy_volume_atlas_leaves_other_texels_alone():
    store = cloud()
    nx, ny, nz = 5, 4, 3
    atlas = np.full((nz, ny, 4 * nx, 4), -9.0, dtype=np.float32)
    view = atlas.reshape(nz, ny, 4, nx, 4).transpose(0, 1, 3, 2, 4)[:, :, :, :3, :]
    assert store.sample_volume(ORIGIN, CELL, (nx, ny, nz), bands=1, unity=True, out=view) is view
    packed = store.sample_volume(ORIGIN, CELL, (nx, ny, nz), bands=1, unity=True)
    for k in range(3):
        assert atlas[:, :, k * nx:(k + 1) * nx, :].tobytes() == np.ascontiguousarray(packed[:, :, :, k, :]).tobytes()
    assert np.all(atlas[:, :, 3 * nx:, :] == -9.0)


def test_bad_arguments_are_refused():
    store = cloud()
    for dims, needle in [((0, 4, 4), "dims[0]"), ((4, 33, 4), "33")]:
        with pytest.raises(Error) as raised:
            store.sample_volume(ORIGIN, CELL, dims)
        assert raised.value.status == Status.INVALID_ARGUMENT and needle in str(raised.value)
    with pytest.raises(Error):
        store.sample_volume([0, math.nan, 0], CELL, (4, 4, 4))
    with pytest.raises(Error):
        store.sample_volume(ORIGIN, [0.1, 0, 0.1], (4, 4, 4))
    with pytest.raises(Error):
        store.sample_volume(ORIGIN, math.inf, (4, 4, 4))
    with pytest.raises(ValueError):
        store.sample_volume(ORIGIN, CELL, (4, 4))
    with pytest.raises(ValueError):
        store.sample_volume(ORIGIN, CELL, (4, 4, -1))
    with pytest.raises(ValueError):
        store.sample_volume(ORIGIN, CELL, (4, 4, 4), out=np.empty((4, 4, 4, 12), np.float32))
    with pytest.raises(ValueError):
        store.sample_volume(ORIGIN, CELL, (4, 4, 4), out=np.empty((4, 4, 4, 27), np.float32)[::-1])
    with pytest.raises(ValueError):
        store.sample_volume(ORIGIN, CELL, (4, 4, 4), bands=3)
    # A single number is the same spacing on each axis.
    assert store.sample_volume(ORIGIN, 0.25, (3, 3, 3)).tobytes() == \
        store.sample_volume(ORIGIN, [0.25, 0.25, 0.25], (3, 3, 3)).tobytes()
