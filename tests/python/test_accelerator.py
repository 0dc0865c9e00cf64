"""prism.Accelerator: every backend over NumPy arrays, against brute force, an independent
double-precision ray-triangle test, and its own occluded()."""

import threading

import numpy as np
import pytest

import prism

BACKENDS = ["brute", "bvh", "embree"]
FIELDS = ["t", "u", "v", "geom_id", "prim_id", "hit"]


def same_bits(a, b):
    """Whether two arrays hold the same values bit for bit (floats compared as integers)."""
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype == np.float32:
        return np.array_equal(a.view(np.uint32), b.view(np.uint32))
    return np.array_equal(a, b)


@pytest.fixture(scope="module")
def scene(cornell_mesh, random_rays):
    """The Cornell box mesh and 3000 rays from inside its box."""
    vertices, indices = cornell_mesh
    origins, directions = random_rays(3000, vertices.min(axis=0), vertices.max(axis=0), seed=1)
    return vertices, indices, origins, directions


@pytest.fixture(scope="module")
def brute(scene):
    vertices, indices, origins, directions = scene
    accel = prism.Accelerator("brute", vertices, indices)
    return accel, accel.intersect(origins, directions)


def test_every_backend_is_listed():
    assert prism.accelerators() == BACKENDS


@pytest.mark.parametrize("name", BACKENDS)
def test_results_have_the_documented_arrays(name, scene):
    vertices, indices, origins, directions = scene
    accel = prism.Accelerator(name, vertices, indices)
    assert accel.name == name
    assert accel.triangle_count == len(indices)
    hits = accel.intersect(origins, directions)
    assert sorted(hits) == sorted(FIELDS)
    expected = {"t": np.float32, "u": np.float32, "v": np.float32, "geom_id": np.int64,
                "prim_id": np.int64, "hit": np.bool_}
    for field, dtype in expected.items():
        assert hits[field].dtype == dtype, field
        assert hits[field].shape == (len(origins),), field
    hit = hits["hit"]
    assert 0 < hit.sum() < len(hit)  # rays escape through the open front, others hit
    assert np.all(np.isinf(hits["t"][~hit]))
    assert np.all(hits["prim_id"][~hit] == -1) and np.all(hits["geom_id"][~hit] == -1)
    assert np.all(hits["u"][~hit] == 0) and np.all(hits["v"][~hit] == 0)
    assert np.all(hits["geom_id"][hit] == 0)
    assert np.all((hits["prim_id"][hit] >= 0) & (hits["prim_id"][hit] < len(indices)))
    assert np.all(hits["t"][hit] >= 0)


def test_bvh_equals_brute_force_bit_for_bit(scene, brute):
    vertices, indices, origins, directions = scene
    _, expected = brute
    for params in [{}, {"split": "median", "layout": "bvh2"}, {"layout": "bvh4"}]:
        hits = prism.Accelerator("bvh", vertices, indices, **params).intersect(origins,
                                                                               directions)
        for field in FIELDS:
            assert same_bits(hits[field], expected[field]), (params, field)


def test_embree_agrees_with_brute_force_within_the_design_tolerance(scene, brute):
    # DESIGN.md: hit and miss agree, |dt| <= 1e-4 max(1, t), other primitives only at ties.
    vertices, indices, origins, directions = scene
    _, expected = brute
    hits = prism.Accelerator("embree", vertices, indices).intersect(origins, directions)
    assert np.array_equal(hits["hit"], expected["hit"])
    hit = expected["hit"]
    t, t_brute = hits["t"][hit].astype(np.float64), expected["t"][hit].astype(np.float64)
    assert np.all(np.abs(t - t_brute) <= 1e-4 * np.maximum(1.0, t_brute))
    # The same primitive (nearly always) gives the same bits: embree.refine recomputes t, u, v
    # with prism's own triangle test.
    same_prim = hits["prim_id"] == expected["prim_id"]
    assert same_prim.mean() > 0.999
    for field in ["t", "u", "v"]:
        assert same_bits(hits[field][same_prim], expected[field][same_prim]), field


def moller_trumbore(origin, direction, p0, p1, p2):
    """t, u, v of the ray against triangles (p0, p1, p2: T x 3) in double precision, NaN where
    it misses a triangle or hits behind the origin."""
    e1, e2 = p1 - p0, p2 - p0
    pvec = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, pvec)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        tvec = origin - p0
        u = np.einsum("ij,ij->i", tvec, pvec) * inv
        qvec = np.cross(tvec, e1)
        v = (qvec @ direction) * inv
        t = np.einsum("ij,ij->i", e2, qvec) * inv
    ok = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
    return np.where(ok, t, np.nan), u, v


def test_hits_match_an_independent_double_precision_test(scene, brute):
    vertices, indices, origins, directions = scene
    tri = vertices.astype(np.float64)[indices.astype(np.int64)]
    p0, p1, p2 = tri[:, 0], tri[:, 1], tri[:, 2]
    hits = prism.Accelerator("bvh", vertices, indices).intersect(origins[:40], directions[:40])
    for k in range(40):
        t, u, v = moller_trumbore(origins[k].astype(np.float64),
                                  directions[k].astype(np.float64), p0, p1, p2)
        if np.all(np.isnan(t)):
            assert not hits["hit"][k], k
            continue
        assert hits["hit"][k], k
        best = int(np.nanargmin(t))
        prim = int(hits["prim_id"][k])
        # The closest triangle, unless another one is as close (a shared edge: a tie).
        assert prim == best or abs(t[prim] - t[best]) <= 1e-6 * max(1.0, t[best]), k
        assert hits["t"][k] == pytest.approx(t[best], rel=1e-5, abs=1e-6), k
        assert hits["u"][k] == pytest.approx(u[prim], abs=1e-4), k
        assert hits["v"][k] == pytest.approx(v[prim], abs=1e-4), k


@pytest.mark.parametrize("name", BACKENDS)
def test_occluded_is_the_hit_mask(name, scene):
    vertices, indices, origins, directions = scene
    accel = prism.Accelerator(name, vertices, indices)
    tmax = np.linspace(0.0, 2.0, len(origins), dtype=np.float32)
    occluded = accel.occluded(origins, directions, 0.0, tmax)
    assert occluded.dtype == np.bool_ and occluded.shape == (len(origins),)
    assert np.array_equal(occluded, accel.intersect(origins, directions, 0.0, tmax)["hit"])
    assert 0 < occluded.sum() < len(occluded)


def test_ray_bounds_are_numbers_or_arrays(scene):
    vertices, indices, origins, directions = scene
    accel = prism.Accelerator("bvh", vertices, indices)
    n = len(origins)
    full = accel.intersect(origins, directions)
    # tmax cuts hits off; tmin hides the near ones, and a negative tmin counts as 0.
    cut = accel.intersect(origins, directions, tmax=0.5)
    assert np.array_equal(cut["hit"], full["hit"] & (full["t"] <= 0.5))
    per_ray = accel.intersect(origins, directions, np.full(n, -1.0), np.full(n, 0.5))
    for field in FIELDS:
        assert same_bits(per_ray[field], cut[field]), field
    far = accel.intersect(origins, directions, tmin=0.3)
    assert np.all(far["t"][far["hit"]] >= 0.3)
    # A ray that cannot hit anything misses: zero direction, NaN, inverted bounds.
    bad = directions[:3].copy()
    bad[0] = 0.0
    bad[1, 0] = np.nan
    tmin = np.array([0.0, 0.0, 2.0], dtype=np.float32)
    tmax = np.array([np.inf, np.inf, 1.0], dtype=np.float32)
    assert not accel.intersect(origins[:3], bad, tmin, tmax)["hit"].any()
    assert not accel.occluded(origins[:3], bad, tmin, tmax).any()


def test_float64_and_list_inputs_are_rounded_to_float32(scene):
    vertices, indices, origins, directions = scene
    accel = prism.Accelerator("bvh", vertices.astype(np.float64), indices.astype(np.int64))
    expected = prism.Accelerator("bvh", vertices, indices).intersect(origins[:20], directions[:20])
    hits = accel.intersect(origins[:20].astype(np.float64), directions[:20].tolist())
    for field in FIELDS:
        assert same_bits(hits[field], expected[field]), field


def test_no_rays_give_empty_arrays(scene):
    vertices, indices, _, _ = scene
    accel = prism.Accelerator("embree", vertices, indices)
    hits = accel.intersect(np.zeros((0, 3)), np.zeros((0, 3)))
    assert all(hits[field].shape == (0,) for field in FIELDS)
    assert accel.occluded(np.zeros((0, 3)), np.zeros((0, 3))).shape == (0,)


@pytest.mark.parametrize("name", BACKENDS)
def test_spheres_are_geometry_one(name):
    vertices = np.array([[-1, -1, 2], [1, -1, 2], [-1, 1, 2]], dtype=np.float32)
    indices = np.array([[0, 1, 2]])
    spheres = np.array([[5, 0, 2, 1], [0, 10, 2, 1]], dtype=np.float32)
    accel = prism.Accelerator(name, vertices, indices, spheres=spheres)
    assert accel.sphere_count == 2
    origins = np.zeros((3, 3), dtype=np.float32)
    directions = np.array([[-0.5, -0.5, 2], [5, 0, 2], [0, 10, 2]], dtype=np.float32)
    hits = accel.intersect(origins, directions)
    assert hits["hit"].all()
    assert hits["geom_id"].tolist() == [0, 1, 1]
    assert hits["prim_id"].tolist() == [0, 0, 1]
    assert hits["t"][0] == 1.0


def test_parameters_without_and_with_their_prefix(scene):
    vertices, indices, origins, directions = scene
    a = prism.Accelerator("bvh", vertices, indices, max_leaf_size=2, split="median")
    b = prism.Accelerator("bvh", vertices, indices, **{"bvh.max_leaf_size": 2,
                                                        "bvh.split": "median"})
    assert a.params == b.params
    assert "bvh.max_leaf_size=2" in a.params
    assert a.stats["leaves"] == b.stats["leaves"] > 0
    e = prism.Accelerator("embree", vertices, indices, refine=False, quality="high")
    assert "embree.refine=false" in e.params
    assert e.stats["build_ms"] >= 0


def test_two_python_threads_query_at_once(scene, brute):
    # The GIL is released during queries: two threads at once finish, with the same results.
    vertices, indices, origins, directions = scene
    _, expected = brute
    accel = prism.Accelerator("bvh", vertices, indices)
    results = [None, None]

    def query(i):
        for _ in range(5):
            results[i] = accel.intersect(origins, directions)

    threads = [threading.Thread(target=query, args=(i,)) for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=120)
        assert not thread.is_alive()
    for result in results:
        for field in FIELDS:
            assert same_bits(result[field], expected[field]), field


def test_a_thread_limit_gives_the_same_results(scene, brute):
    vertices, indices, origins, directions = scene
    _, expected = brute
    accel = prism.Accelerator("embree", vertices, indices, threads=1)
    assert accel.threads == 1
    hits = prism.Accelerator("bvh", vertices, indices, threads=1).intersect(origins, directions)
    for field in FIELDS:
        assert same_bits(hits[field], expected[field]), field
    assert np.array_equal(accel.occluded(origins, directions), expected["hit"])
