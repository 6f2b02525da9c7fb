"""Scenes, collision checks, clearances and edge checks of urkin.planning.

Signed distances are held to closest points computed another way (clipping into the box,
clamping onto the cylinder, dense sampling of a capsule's segment); checks to their
definitions; edge sampling to the distance every sphere centre really moves.
"""

import numpy as np
import pytest

import urkin
from urkin import planning
from urkin.transforms import random_rotations

UR5 = urkin.robot("ur5")
MODEL = planning.sphere_model(UR5)
# the table top 1 cm below the mounting plane (a shoulder sphere reaches 7 mm below it)
TABLE = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
UP = np.array([0, -np.pi / 2, 0, -np.pi / 2, 0, 0])


def test_box_distances_against_the_clipped_closest_point(rng):
    R = random_rotations(1, seed=3)[0]
    box = planning.Box([0.2, -0.1, 0.3], [0.3, 0.2, 0.1], R)
    scene = planning.Scene(boxes=[box])
    points = rng.uniform(-0.5, 0.8, (2000, 3))
    local = (points - box.centre) @ R
    half = box.size / 2
    closest = np.clip(local, -half, half)
    outside = np.linalg.norm(local - closest, axis=1)
    inside = -np.min(half - np.abs(local), axis=1)
    expected = np.where(np.all(np.abs(local) <= half, axis=1), inside, outside)
    np.testing.assert_allclose(scene.signed_distances(points)[:, 0], expected, atol=1e-12)


def test_cylinder_distances_against_the_clamped_closest_point(rng):
    cylinder = planning.Cylinder([0.1, 0.2, 0.0], [1.0, 1.0, 0.0], radius=0.1, length=0.4)
    scene = planning.Scene(cylinders=[cylinder])
    points = rng.uniform(-0.5, 0.6, (2000, 3))
    d = points - cylinder.centre
    t = d @ cylinder.axis
    radial = d - t[:, None] * cylinder.axis
    rho = np.linalg.norm(radial, axis=1)
    tc = np.clip(t, -0.2, 0.2)
    rc = np.minimum(rho, 0.1)
    direction = radial / rho[:, None]
    closest = cylinder.centre + tc[:, None] * cylinder.axis + rc[:, None] * direction
    outside = np.linalg.norm(points - closest, axis=1)
    inside = -np.minimum(0.1 - rho, 0.2 - np.abs(t))
    expected = np.where((rho <= 0.1) & (np.abs(t) <= 0.2), inside, outside)
    np.testing.assert_allclose(scene.signed_distances(points)[:, 0], expected, atol=1e-12)


def test_sphere_and_capsule_distances(rng):
    a, b = np.array([0.0, 0.0, 0.0]), np.array([0.3, 0.1, -0.2])
    scene = planning.Scene(
        spheres=[planning.Sphere([0.1, 0.1, 0.1], 0.05)], capsules=[planning.Capsule(a, b, 0.04)]
    )
    points = rng.uniform(-0.4, 0.5, (500, 3))
    segment = a + np.linspace(0, 1, 200_001)[:, None] * (b - a)
    nearest = np.array([np.min(np.linalg.norm(segment - p, axis=1)) for p in points])
    got = scene.signed_distances(points)
    np.testing.assert_allclose(got[:, 0], np.linalg.norm(points - 0.1, axis=1) - 0.05, atol=1e-12)
    np.testing.assert_allclose(got[:, 1], nearest - 0.04, atol=1e-6)
    assert scene.names == ("sphere 0", "capsule 0")


def test_scene_keeps_leading_axes_and_refuses_bad_obstacles():
    scene = planning.Scene(boxes=[{"centre": [0, 0, 0], "size": [1, 1, 1]}])
    assert scene.signed_distances(np.zeros((2, 3, 3))).shape == (2, 3, 1)
    assert planning.Scene().signed_distances(np.zeros((4, 3))).shape == (4, 0)
    with pytest.raises(ValueError, match="box size must be three positive edge lengths"):
        planning.Box([0, 0, 0], [1, -1, 1])
    with pytest.raises(ValueError, match="rotation"):
        planning.Box([0, 0, 0], [1, 1, 1], rotation=np.ones((3, 3)))
    with pytest.raises(ValueError, match="cylinder axis must be a non-zero direction"):
        planning.Cylinder([0, 0, 0], [0, 0, 0], 0.1, 0.2)
    # coordinates and sizes far beyond a robot cell: their squares lose precision, and from
    # 1e154 m overflow (a cylinder, sphere or capsule there vanished from the checks)
    for make in (
        lambda: planning.Box([1e7, 0, 0], [1, 1, 1]),
        lambda: planning.Box([0, 0, 0], [1, 1e300, 1]),
        lambda: planning.Cylinder([0, 0, 4e299], [0, 0, 1], 0.05, 1e300),
        lambda: planning.Sphere([0, 0, 1e200], 1e200),
        lambda: planning.Capsule([0, 0, -1e160], [0, 0, 1e160], 0.05),
    ):
        with pytest.raises(ValueError, match=r"within ±1e\+06 m of the robot"):
            make()
    # a direction of any size keeps its direction (its norm would overflow or underflow)
    for axis, unit in (([3e300, 0, 4e300], [0.6, 0, 0.8]), ([5e-324, 0, 0], [1, 0, 0])):
        assert planning.Cylinder([0, 0, 0], axis, 0.1, 0.2).axis.tolist() == unit
    with pytest.raises(ValueError, match="sphere radius must be positive"):
        planning.Sphere([0, 0, 0], 0.0)
    with pytest.raises(ValueError, match="box centre must be a 3-vector"):
        planning.Box([0, 0], [1, 1, 1])
    with pytest.raises(TypeError, match=r"boxes\[0\] must be a planning.Box"):
        planning.Scene(boxes=[planning.Sphere([0, 0, 0], 1.0)])
    with pytest.raises(ValueError, match="points must have shape"):
        scene.signed_distances([1.0, 2.0])
    with pytest.raises(TypeError, match="box name must be a str or None; got int 5"):
        planning.Box([0, 0, 0], [1, 1, 1], name=5)
    with pytest.raises(ValueError, match=r"sphere radius must be one number \(metres\)"):
        planning.Sphere([0, 0, 0], [0.1, 0.2])


def test_is_free_matches_the_sign_of_the_clearance(rng):
    Q = rng.uniform(-np.pi, np.pi, (3000, 6))
    free = planning.is_free(MODEL, TABLE, Q)
    c = planning.clearance(MODEL, TABLE, Q)
    np.testing.assert_array_equal(free, c.distance > 0)
    assert free.any() and not free.all()
    grid = Q[:12].reshape(3, 4, 6)
    assert planning.is_free(MODEL, TABLE, grid).shape == (3, 4)
    assert planning.clearance(MODEL, TABLE, grid).distance.shape == (3, 4)
    assert planning.is_free(MODEL, TABLE, UP) is True


def test_broad_phase_gives_the_verdicts_of_every_sphere(rng):
    """is_free tests groups' bounding balls first and only then their spheres; its verdicts
    are those of every sphere against every obstacle and every self pair (clearance, which
    tests them all), for a gripper's many small spheres on the tool frame and a cluttered
    scene, at configurations drawn near contact as well as at random."""
    model = MODEL.with_tool_spheres(
        [[0, 0, 0.03], [0.03, 0, 0.09], [-0.03, 0, 0.09], [0, 0, 0.13]], [0.04, 0.02, 0.02, 0.015]
    )
    groups = planning.checks._groups(model)
    for g, members in enumerate(groups.members):
        members = members[members >= 0]
        assert np.all(model.frames[members] == groups.frames[g])
        reach = np.linalg.norm(model.centres[members] - groups.centres[g], axis=1)
        assert np.all(reach + model.radii[members] <= groups.radii[g] + 1e-12)
    scene = planning.Scene(
        boxes=[
            planning.Box([0.45, 0.0, 0.2], [0.3, 0.02, 0.6], name="shelf side"),
            planning.Box([0.45, 0.2, 0.3], [0.3, 0.4, 0.02], random_rotations(seed=rng)),
        ],
        cylinders=[planning.Cylinder([0.3, -0.3, 0.1], [0, 0, 1], 0.03, 0.14)],
        spheres=[planning.Sphere([-0.3, 0.3, 0.4], 0.1)],
        capsules=[planning.Capsule([-0.4, -0.2, 0.1], [-0.2, -0.4, 0.5], 0.03)],
    )
    Q = np.concatenate([rng.uniform(-np.pi, np.pi, (3000, 6)), rng.normal(UP, 0.6, (3000, 6))])
    c = planning.clearance(model, scene, Q)
    clear = np.abs(c.distance) > 1e-9
    free = planning.is_free(model, scene, Q)
    np.testing.assert_array_equal(free[clear], c.distance[clear] > 0)
    assert 0.1 < free.mean() < 0.9
    # batches of every size the checks see (their frames are computed in two ways)
    pieces = np.split(np.arange(len(Q)), np.cumsum([1, 2, 3, 5, 8, 40, 900, 1001]))
    for rows in pieces:
        np.testing.assert_array_equal(planning.is_free(model, scene, Q[rows]), free[rows])
    np.testing.assert_array_equal([planning.is_free(model, scene, q) for q in Q[:50]], free[:50])
    assert np.any(c.obstacle >= 0) and np.any(c.other >= 0)  # both kinds of contact occur


def test_touch_tests_agree_with_signed_distances_for_every_kind(rng):
    """The boolean check (squared distances; bounding balls first for small boxes, small
    cylinders and capsules) gives the verdict of the exact signed distances, ball by ball, for
    boxes and cylinders (small and large), spheres and capsules."""
    scene = planning.Scene(
        boxes=[
            planning.Box([0.1, -0.2, -0.3], [1.0, 0.8, 0.05], random_rotations(seed=rng)),
            planning.Box(rng.normal(size=3) * 0.3, [0.1, 0.3, 0.05], random_rotations(seed=rng)),
        ],
        cylinders=[
            planning.Cylinder([0.2, -0.1, 0.3], [1, 2, 2], 0.07, 0.4),  # small: culled first
            planning.Cylinder([-0.4, -0.3, 0.0], [0, 1, 1], 0.1, 0.8),  # large: tested densely
        ],
        spheres=[planning.Sphere([-0.3, 0.2, 0.1], 0.12)],
        capsules=[
            planning.Capsule([0, 0.4, 0], [0.3, 0.4, 0.2], 0.05),
            planning.Capsule([0.5, 0.5, 0.5], [0.5, 0.5, 0.5], 0.05),  # a ball
        ],
    )
    P = rng.uniform(-0.7, 0.7, (40_000, 3))
    r = rng.uniform(0.0, 0.1, len(P))
    gap = scene.signed_distances(P) - r[:, None]
    clear = np.abs(gap).min(axis=1) > 1e-9  # away from touching by more than round-off
    np.testing.assert_array_equal(scene._touches(P.T, r)[clear], (gap <= 0).any(axis=1)[clear])
    # the dense test of a few points: the squared gap to the nearest obstacle
    np.testing.assert_array_equal((scene._gaps2(P) <= r * r)[clear], (gap <= 0).any(axis=1)[clear])
    outside = np.maximum(scene.signed_distances(P), 0.0).min(axis=1)
    np.testing.assert_allclose(np.sqrt(scene._gaps2(P)), outside, atol=1e-9)
    assert 0.01 < np.mean((gap <= 0).any(axis=1)) < 0.99
    for k in range(len(scene)):
        assert (gap[:, k] <= 0).any()  # every obstacle is touched by some ball


def test_clearance_is_the_smallest_gap_of_every_pair(rng):
    Q = rng.uniform(-np.pi, np.pi, (50, 6))
    c = planning.clearance(MODEL, TABLE, Q)
    W = MODEL.place(Q)
    moving = MODEL.frames > 0
    env = TABLE.signed_distances(W[:, moving])[..., 0] - MODEL.radii[moving]
    i, j = MODEL.pairs.T
    own = np.linalg.norm(W[:, i] - W[:, j], axis=-1) - MODEL.radii[i] - MODEL.radii[j]
    # the base and upper arm, the forearm and wrist 2, the forearm and wrist 3 (turned about
    # joint 6): tested on their tabulated meshes
    assert [pair.frames for pair in MODEL.meshes] == [(0, 2), (3, 5), (3, 6)]
    tabulated = np.array([pair.lower_bound(Q) for pair in MODEL.meshes])  # (3, N)
    expected = np.minimum(np.minimum(env.min(1), own.min(1)), tabulated.min(axis=0))
    np.testing.assert_allclose(c.distance, expected, atol=1e-12)
    is_self = c.obstacle < 0
    np.testing.assert_array_equal(is_self, c.other >= 0)
    assert np.any(c.distance == tabulated.min(axis=0))  # a tabulated pair is the closest
    for pair, bound in zip(MODEL.meshes, tabulated):
        a, b = (planning.FRAME_NAMES[f] for f in pair.frames)
        for q in Q[c.distance == bound][:2]:
            assert f"the {a} and {b} meshes" in planning.explain(MODEL, planning.Scene(), q)


def test_explain_names_the_pair_and_the_depth():
    assert planning.explain(MODEL, TABLE, [0, 0.5, 0, 0, 0, 0]).startswith(
        "in collision: upper arm sphere"
    )
    assert "box 'table'" in planning.explain(MODEL, TABLE, [0, 0.5, 0, 0, 0, 0])
    assert planning.explain(MODEL, TABLE, UP).startswith("free: the closest pair is")
    stick = planning.SphereModel.from_rows(
        UR5, [[1, 0, 0, 0, 0.05], [3, 0, 0, 0, 0.05]], pairs=[[0, 1]]
    )
    folded = [0, 0, np.pi, 0, 0, 0]  # the forearm folded back onto the shoulder
    text = planning.explain(stick, planning.Scene(), folded)
    assert "(self-collision)" in text
    assert planning.explain(
        planning.SphereModel.from_rows(UR5, [[1, 0, 0, 0, 0.05]]), planning.Scene(), UP
    ).startswith("free: nothing to collide with")
    with pytest.raises(ValueError, match="explain takes one configuration"):
        planning.explain(MODEL, TABLE, np.zeros((2, 6)))


def test_edges_catch_a_collision_between_free_ends():
    assert planning.is_free(MODEL, TABLE, UP)
    through = UP.copy()
    through[1] += np.pi  # the upper arm pointing straight down: in the table
    assert not planning.is_free(MODEL, TABLE, through)
    around = UP.copy()
    around[0] += 2.0
    result = planning.edges_free(MODEL, TABLE, [UP, UP], [around, through])
    np.testing.assert_array_equal(result, [True, False])


CLUTTER = planning.Scene(
    boxes=[
        planning.Box([0.45, 0.0, 0.2], [0.3, 0.02, 0.6], name="shelf side"),
        planning.Box([0.4, 0.25, 0.35], [0.3, 0.4, 0.02], name="shelf"),
        planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table"),
    ],
    cylinders=[planning.Cylinder([0.3, -0.3, 0.1], [0, 0, 1], 0.03, 0.14)],
    spheres=[planning.Sphere([-0.3, 0.3, 0.4], 0.1)],
    capsules=[planning.Capsule([-0.4, -0.2, 0.1], [-0.2, -0.4, 0.5], 0.03)],
)


def test_grown_checks_are_checks_of_grown_spheres(rng):
    """Grown by a margin, a configuration counts as colliding when any grown sphere touches an
    obstacle or a grown paired sphere: the verdicts of a model with larger radii."""
    rows = np.column_stack([MODEL.frames, MODEL.centres, MODEL.radii])
    Q = np.concatenate([rng.uniform(-np.pi, np.pi, (2000, 6)), rng.normal(UP, 0.6, (2000, 6))])
    for margin in (0.0, 0.001, 0.002):  # a shoulder sphere is 3 mm above the table
        grown = rows.copy()
        grown[:, 4] += margin
        bigger = planning.SphereModel.from_rows(UR5, grown, pairs=MODEL.pairs)
        plain = planning.SphereModel.from_rows(UR5, rows, pairs=MODEL.pairs)
        grow = np.full((len(Q), len(plain)), margin)
        got, as_they_are = planning.checks._hits(plain, CLUTTER, Q, grow)
        c = planning.clearance(bigger, CLUTTER, Q).distance
        clear = np.abs(c) > 1e-9
        np.testing.assert_array_equal(got[clear], c[clear] <= 0)
        np.testing.assert_array_equal(as_they_are, ~planning.is_free(plain, CLUTTER, Q))
        assert 0.1 < got.mean() < 0.9
    # with a tabulated mesh pair too, the verdicts as they are come with the grown ones
    grow = rng.uniform(0.0, 0.02, (len(Q), len(MODEL) + len(MODEL.meshes)))
    got, as_they_are = planning.checks._hits(MODEL, CLUTTER, Q, grow)
    np.testing.assert_array_equal(as_they_are, ~planning.is_free(MODEL, CLUTTER, Q))
    assert np.all(got >= as_they_are) and np.any(got > as_they_are)
    # the dense path (no broad phase, for a few configurations): the same verdicts
    assert len(Q) > planning.checks._DENSE
    for rows in np.array_split(np.arange(len(Q)), 125):  # 32 at a time
        few = planning.checks._dense_hits(MODEL, CLUTTER, Q[rows], grow[rows])
        np.testing.assert_array_equal(few[0], got[rows])
        np.testing.assert_array_equal(few[1], as_they_are[rows])
    # a tabulated mesh pair counts within the margin of its lower bound; every pair bounded
    # at once, cells ruled out by their floor skipped, gives each pair's own bound
    tables = planning.spheres._tables(MODEL.meshes)
    for margin in (0.0, 0.01, 0.03):
        rows, pairs, near = tables.bounds(Q, np.full((len(Q), len(MODEL.meshes)), margin))
        for p, pair in enumerate(MODEL.meshes):
            bound = pair.lower_bound(Q)
            within = np.zeros(len(Q), dtype=bool)
            within[rows[pairs == p]] = near[pairs == p] <= margin
            np.testing.assert_array_equal(within, bound <= margin)  # no cell skipped wrongly
            np.testing.assert_array_equal(near[pairs == p], bound[rows[pairs == p]])


@pytest.mark.parametrize("known", [0, 1, 2])
def test_edge_verdicts_are_those_of_every_sample(rng, known):
    """edges_free proves blocks of an edge free with grown spheres and checks the rest: its
    verdicts are exactly those of checking every sample, on edges in a cluttered scene that
    are mostly free, mostly blocked, or graze an obstacle, long and short."""
    Q = rng.normal(UP, 0.8, (4000, 6))
    Q = Q[planning.is_free(MODEL, CLUTTER, Q)]
    A = Q[:300]
    steps = rng.normal(size=A.shape)
    steps *= rng.choice([0.02, 0.3, 1.0, 2.5], (len(A), 1)) / np.linalg.norm(steps, axis=1)[:, None]
    B = A + steps
    counts = planning.edge_samples(MODEL, A, B)
    every = np.array(
        [
            planning.is_free(MODEL, CLUTTER, a + np.linspace(0, 1, n + 1)[:, None] * (b - a)).all()
            for a, b, n in zip(A, B, counts)
        ]
    )
    keep = np.ones(len(A), dtype=bool)
    if known == 2:  # the function trusts known ends: give it only edges whose ends are free
        keep = planning.is_free(MODEL, CLUTTER, B)
    travel = planning.checks._travels(MODEL, A, B, planning.checks.RESOLUTION)
    got = planning.checks._edges_free(
        MODEL, CLUTTER, A[keep], B[keep], travel[keep], planning.checks.RESOLUTION, known=known
    )
    np.testing.assert_array_equal(got, every[keep])
    assert 0.2 < every[keep].mean() < 0.99 and not every[keep].all()
    one = [planning.edges_free(MODEL, CLUTTER, a, b) for a, b in zip(A[:40], B[:40])]
    np.testing.assert_array_equal(one, every[:40])
    # one edge at a time (its own path, planned once per sample count), proving or not
    for prove in (True, False):
        single = [
            planning.checks._edges_free(
                MODEL,
                CLUTTER,
                A[k : k + 1],
                B[k : k + 1],
                travel[k : k + 1],
                planning.checks.RESOLUTION,
                known=known,
                prove=prove,
            )[0]
            for k in np.flatnonzero(keep)[:120]
        ]
        np.testing.assert_array_equal(single, got[:120])


def test_certified_edges_are_free_everywhere_and_open_ones_are_certified(rng):
    """certify_edges proves an edge free between samples too: every edge it certifies is free
    at samples 0.2 mm apart; edges that collide are never certified; most free edges are."""
    Q = rng.normal(UP, 0.8, (3000, 6))
    Q = Q[planning.is_free(MODEL, CLUTTER, Q)]
    A = Q[:120]
    steps = rng.normal(size=A.shape)
    steps *= rng.choice([0.05, 0.3, 1.0], (len(A), 1)) / np.linalg.norm(steps, axis=1)[:, None]
    B = A + steps
    proven = planning.certify_edges(MODEL, CLUTTER, A, B)
    sampled = planning.edges_free(MODEL, CLUTTER, A, B, resolution=0.0002)
    assert np.all(sampled[proven])  # proven free: free at every fine sample
    assert proven.sum() >= 0.9 * sampled.sum() and not sampled.all()
    assert planning.certify_edges(MODEL, CLUTTER, A[0], B[0]) == proven[0]
    assert planning.certify_edges(
        MODEL, CLUTTER, A[:6].reshape(2, 3, 6), B[:6].reshape(2, 3, 6)
    ).shape == (2, 3)
    with pytest.raises(ValueError, match="finest must be a positive distance"):
        planning.certify_edges(MODEL, CLUTTER, A[0], B[0], finest=0)


def test_certification_never_checks_more_than_max_samples_pieces_in_a_round(monkeypatch):
    """Near contact the pieces multiply at each round; when the next round would check more
    than MAX_SAMPLES of them, the edges still open are left unproven (False), not checked in
    an ever larger batch.  The edge: the upright arm turning about its base 1 mm below a
    ceiling, so every piece stays 1 mm from contact."""
    top = float(np.max(MODEL.place(UP)[:, 2] + MODEL.radii))
    ceiling = planning.Scene(boxes=[planning.Box([0, 0, top + 0.051], [4, 4, 0.1])])
    turned = UP + np.array([1.0, 0, 0, 0, 0, 0])
    assert abs(float(planning.clearance(MODEL, ceiling, turned).distance) - 0.001) < 1e-9
    sizes = []
    hits = planning.checks._hits

    def counted(model, scene, Q, grow):
        sizes.append(len(Q))
        return hits(model, scene, Q, grow)

    monkeypatch.setattr(planning.checks, "_hits", counted)
    assert planning.certify_edges(MODEL, ceiling, UP, turned)  # 1 mm clear: proven
    assert len(sizes) >= 3 and sizes[2] > sizes[1] > sizes[0]  # the pieces multiplied
    cap = 5 * sizes[2] // 6  # between two and three times the pieces left open by round 2
    monkeypatch.setattr(planning.checks, "MAX_SAMPLES", cap)
    sizes.clear()
    assert not planning.certify_edges(MODEL, ceiling, UP, turned)  # left open: not proven
    assert sizes and max(sizes) <= cap


def _mounted_gripper_model() -> planning.SphereModel:
    """The UR5's spheres on an arm mounted on a tilted base, with two spheres on a tool."""
    from urkin.transforms import make_transform

    base = make_transform(random_rotations(1, seed=4)[0], [0.2, -0.1, 0.9])
    arm = UR5.with_base(base).with_tool(make_transform(p=[0.0, 0.02, 0.15]))
    rows = np.column_stack([MODEL.frames, MODEL.centres, MODEL.radii])
    tool = [[7, 0.0, 0.0, 0.05, 0.04], [7, 0.03, 0.0, 0.12, 0.03]]
    return planning.SphereModel.from_rows(arm, np.vstack([rows, tool]), pairs=MODEL.pairs)


@pytest.mark.parametrize("model", [MODEL, _mounted_gripper_model()], ids=["ur5", "mounted"])
def test_edge_samples_bound_how_far_every_sphere_moves(rng, model):
    # the count bounds the largest move of any centre between neighbouring samples, measured
    # on a sampling 16 times finer; the edges are long (up to 2 rad a joint) and short
    for resolution, size in ((0.01, 2.0), (0.003, 1.0), (0.01, 0.05)):
        A = rng.uniform(-np.pi, np.pi, (20, 6))
        B = A + rng.uniform(-size, size, (20, 6))
        counts = planning.edge_samples(model, A, B, resolution)
        for a, b, n in zip(A, B, counts):
            t = np.linspace(0, 1, 16 * n + 1)
            W = model.place(a + t[:, None] * (b - a))  # (16n + 1, S, 3)
            steps = np.linalg.norm(np.diff(W, axis=0), axis=-1)  # (16n, S)
            moved = steps.reshape(n, 16, -1).sum(axis=1)  # path length between samples
            assert moved.max() <= resolution * (1 + 1e-9)
        # and it never asks for more samples than the bound by ρ_j alone
        crude = np.ceil((np.abs(B - A) @ planning.checks._reach(model).T).max(1) / resolution)
        assert np.all(counts <= np.maximum(crude, 1))


def test_checks_refuse_bad_arguments():
    with pytest.raises(TypeError, match=r"model must be a planning\.SphereModel"):
        planning.is_free(UR5, TABLE, UP)
    with pytest.raises(TypeError, match=r"scene must be a planning\.Scene"):
        planning.is_free(MODEL, [], UP)
    with pytest.raises(ValueError, match="q must be 6 joint angles"):
        planning.is_free(MODEL, TABLE, [0, 0, 0])
    with pytest.raises(ValueError, match="NaN"):
        planning.clearance(MODEL, TABLE, [0, 0, 0, 0, 0, np.nan])
    with pytest.raises(ValueError, match="qa and qb must have the same shape"):
        planning.edges_free(MODEL, TABLE, UP, np.zeros((2, 6)))
    with pytest.raises(ValueError, match="resolution must be a positive distance"):
        planning.edges_free(MODEL, TABLE, UP, UP, resolution=0.0)
    for call, error in (
        (lambda: planning.edges_free(MODEL, TABLE, UP, UP, resolution="x"), TypeError),
        (lambda: planning.edges_free(MODEL, TABLE, UP, UP, resolution=float("nan")), ValueError),
        (lambda: planning.certify_edges(MODEL, TABLE, UP, UP, finest="x"), TypeError),
        (lambda: planning.shortcut(MODEL, TABLE, [UP, UP], resolution=np.inf), ValueError),
    ):
        with pytest.raises(error, match="must be a positive distance"):
            call()
    for call in (lambda: planning.edge_samples(UR5, UP, UP), lambda: planning.self_pairs("x")):
        with pytest.raises(TypeError, match=r"model must be a planning\.SphereModel"):
            call()


@pytest.mark.parametrize("name", ["UR3", "UR5"])
def test_mesh_speeds_bound_how_far_each_tabulated_link_moves(rng, name):
    """A tabulated pair's column of the speed bounds (what grown checks add to the table's
    margin) bounds how far any point of the second link's mesh — or of the solid wrist 3
    sweeps about joint 6 — moves relative to the first link along the edge: the path length
    of every vertex, measured at 200 samples, on edges long and short, near and far; it is
    the rate at which the table's lower bound can fall, ``Σ |Δq| · reach``."""
    from tests.fit_spheres import mesh_in_dh_frames
    from tests.pair_tables import revolved, split
    from urkin.kinematics import dh_transform

    model = planning.sphere_model(urkin.robot(name))
    meshes, dh = mesh_in_dh_frames(name), model.robot.dh_table()
    A = np.concatenate([rng.uniform(-np.pi, np.pi, (12, 6)), rng.normal(UP, 0.5, (12, 6))])
    B = A + rng.uniform(-1.0, 1.0, A.shape) * rng.choice([0.05, 1.0], (len(A), 1))
    speeds = planning.checks._travels(model, A, B, planning.checks.RESOLUTION)
    t = np.linspace(0, 1, 200)
    for p, pair in enumerate(model.meshes):
        first, second = pair.frames
        j = pair.joints[0]
        points = np.unique(meshes[second].reshape(-1, 3), axis=0)
        if second - first == 3:  # the solid, in the frame before wrist 3's
            T = dh_transform(0.0, *dh[second - 1])
            pieces, bump = split(meshes[second])  # the bump is a sphere of the model
            points = np.unique(revolved(pieces[~bump]).reshape(-1, 3), axis=0)
            points = points @ T[:3, :3].T + T[:3, 3]
        for a, b, bound in zip(A, B, speeds[:, len(model) + p]):
            q = a + t[:, None] * (b - a)
            T = dh_transform(q[:, j], *dh[j]) @ dh_transform(q[:, j + 1], *dh[j + 1])
            moved = points @ T[:, :3, :3].transpose(0, 2, 1) + T[:, None, :3, 3]  # (200, V, 3)
            travelled = np.linalg.norm(np.diff(moved, axis=0), axis=2).sum(axis=0).max()
            assert travelled <= bound + 1e-9, f"{pair.frames}: {travelled} > {bound}"
            # the rate of the table's lower bound, which the checks test
            assert bound == pytest.approx(np.abs(b - a)[j : j + 2] @ pair.reach, rel=1e-12)


def test_edges_certified_near_a_tabulated_contact_are_free_at_every_sample():
    """Short edges of the UR5 where its upper arm passes within a few millimetres of its base
    (their tabulated pair): every edge ``certify_edges`` proves free is free at 101 samples,
    however the table's lower bound varies between its nodes, and ``edges_free``, which
    proves blocks free the same way, gives the verdicts of checking every sample.  (Grown by
    how far the meshes truly move, which near the base is less than how fast the bound can
    fall, 15 of 311 proven edges had samples in contact.)"""
    D = MODEL.meshes[0].distance  # base and upper arm, over joints 1 and 2
    rng = np.random.default_rng(0)
    near = np.argwhere((D > 0.002) & (D < 0.01))
    A = np.tile(UP, (500, 1))
    A[:, :2] = -np.pi + 2 * np.pi * (
        near[rng.choice(len(near), 500)] + rng.uniform(-0.1, 0.1, (500, 2))
    ) / len(D)
    B = A.copy()
    B[:, 0] += rng.uniform(-0.3, 0.3, 500)
    B[:, 1] += rng.uniform(-0.01, 0.01, 500)
    empty = planning.Scene()
    ends_free = planning.is_free(MODEL, empty, A) & planning.is_free(MODEL, empty, B)
    A, B = A[ends_free], B[ends_free]
    proven = planning.certify_edges(MODEL, empty, A, B)
    assert 100 <= proven.sum() < len(A)  # near contact: many proven, not all
    t = np.linspace(0, 1, 101)[:, None]
    samples = A[proven][:, None] + t * (B[proven] - A[proven])[:, None]
    assert planning.is_free(MODEL, empty, samples).all()
    every = [
        planning.is_free(MODEL, empty, a + np.linspace(0, 1, n + 1)[:, None] * (b - a)).all()
        for a, b, n in zip(A, B, planning.edge_samples(MODEL, A, B))
    ]
    verdicts = planning.edges_free(MODEL, empty, A, B)
    np.testing.assert_array_equal(verdicts, every)
    assert 0.3 < verdicts.mean() < 0.95


def test_resolutions_that_would_take_too_many_samples_are_refused_by_name():
    """Before: numpy's "Maximum allowed size exceeded" or "negative dimensions", or minutes of
    checks and gigabytes for a resolution of a nanometre."""
    model = planning.sphere_model(urkin.robot("ur5"))
    qa = np.array([0, -1.57, 0, -1.57, 0, 0.0])
    qb = qa + 0.3
    for call in (
        lambda: planning.edges_free(model, planning.Scene(), qa, qb, resolution=1e-9),
        lambda: planning.edge_samples(model, qa, qb, resolution=1e-300),
    ):
        with pytest.raises(ValueError, match=r"every resolution = .* use a coarser resolution"):
            call()
    with pytest.raises(ValueError, match=r"to finest = 1e-300 m .* use a larger finest"):
        planning.certify_edges(model, planning.Scene(), qa, qb, finest=1e-300)


@pytest.mark.parametrize("offset", [1e5, 5e5, 9e5])
def test_checks_stay_exact_far_from_the_origin(offset):
    """A robot 9e5 m out among obstacles beside it: 0.1 mm of overlap is a collision and 0.1 mm
    of gap is free, for every kind of obstacle (small ones culled, large ones tested densely),
    one configuration or a stack (squared distances are taken of differences, and the cull's
    expansion is written about its obstacles' middle, not the origin)."""
    T = np.eye(4)
    T[:3, 3] = [offset, offset, 0.0]
    model = planning.SphereModel.from_rows(
        urkin.robot("ur5").with_base(T), [[6, 0, 0, 0, 0.05]], pairs=np.zeros((0, 2), int)
    )
    q = np.zeros(6)
    c = model.place(q)[0]
    x = np.array([1.0, 0.0, 0.0])
    for gap in (-1e-4, 1e-4):
        for scene in (
            planning.Scene(spheres=[planning.Sphere(c + (0.15 + gap) * x, 0.1)]),
            planning.Scene(cylinders=[planning.Cylinder(c + (0.45 + gap) * x, [0, 0, 1], 0.4, 1)]),
            planning.Scene(
                cylinders=[planning.Cylinder(c + (0.1 + gap) * x, [0, 0, 1], 0.05, 0.1)]
            ),
            planning.Scene(boxes=[planning.Box(c + (0.1 + gap) * x, [0.1, 0.1, 0.1])]),
            planning.Scene(boxes=[planning.Box(c + (0.55 + gap) * x, [1.0, 1.0, 1.0])]),
        ):
            assert planning.is_free(model, scene, q) == (gap > 0)
            assert np.all(planning.is_free(model, scene, np.tile(q, (50, 1))) == (gap > 0))


def test_a_box_rotation_a_little_off_orthonormal_is_made_a_rotation():
    """check_rotation accepts 1e-6 of error; used as it is, Rᵀ would not undo R and a face 5e4
    m from the centre would move by centimetres."""
    box = planning.Box([0, 0, 0], [1e5, 1e5, 1e5], np.diag([1.0, 1.0, 1 + 4.9e-7]))
    np.testing.assert_allclose(box.rotation.T @ box.rotation, np.eye(3), atol=1e-15)
    R = urkin.transforms.rot_z(0.3)
    assert np.array_equal(planning.Box([0, 0, 0], [1, 1, 1], R).rotation, R)  # kept as given


def test_explain_names_spheres_when_a_sphere_pair_of_two_tabulated_links_is_closest():
    """The UR5's forearm and wrist 3 have a mesh table, and also a sphere pair (wrist 3's extra
    sphere): explain names whichever of the two set the clearance."""
    model = planning.sphere_model(urkin.robot("ur5"))
    Q = urkin.robots.random_configurations(model.robot, 2000, seed=4)
    c = planning.clearance(model, planning.Scene(), Q)
    tabulated = [set(pair.frames) for pair in model.meshes]
    by_spheres = [
        k
        for k in np.flatnonzero((c.other >= 0) & ~c.meshes)
        if {model.frames[c.sphere[k]], model.frames[c.other[k]]} in tabulated
    ]
    assert by_spheres
    for k in by_spheres[:5]:
        text = planning.explain(model, planning.Scene(), Q[k])
        assert "meshes" not in text and model.names[c.sphere[k]] in text
    for k in np.flatnonzero(c.meshes)[:5]:
        assert "meshes" in planning.explain(model, planning.Scene(), Q[k])


def test_obstacles_keep_their_own_numbers():
    """An obstacle copies what it is given, read-only: editing the caller's array afterwards
    neither bypasses the checks (a NaN centre, a negative size) nor changes the scene."""
    centre, size = np.array([0.0, 0.0, -0.06]), np.array([2.0, 2.0, 0.1])
    table = planning.Box(centre, size, name="table")
    size[:] = [-1.0, 2.0, 0.1]
    centre[0] = np.nan
    scene = planning.Scene(boxes=[table])
    down = [0, 0.5, 0, 0, 0, 0]  # the upper arm down through the table
    assert not planning.is_free(MODEL, scene, down)
    assert np.array_equal(table.centre, [0, 0, -0.06]) and np.array_equal(table.size, [2, 2, 0.1])
    for value in (table.centre, table.size, table.rotation):
        assert not value.flags.writeable
    axis = np.array([0.0, 0.0, 1.0])
    rod = planning.Cylinder([0.4, 0, 0], axis, 0.05, 0.5)
    axis[0] = 5.0
    assert np.array_equal(rod.axis, [0, 0, 1]) and not rod.axis.flags.writeable


def test_audited_planning_inputs_get_errors_that_name_them():
    eye = np.eye(3)
    with pytest.raises(ValueError, match="half_a must be half edge lengths ≥ 0"):
        planning.box_separation([0, 0, 0], eye, [-1, 1, 1], [3, 0, 0], eye, [1, 1, 1])
    with pytest.raises(ValueError, match="R_a"):
        planning.box_separation([0, 0, 0], 2 * eye, [1, 1, 1], [3, 0, 0], eye, [1, 1, 1])
    ur3 = urkin.robot("ur3")
    table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    world = planning.World(ur3, planning.sphere_model(ur3), table, cube)  # one block
    assert world.names == ("A",)
    with pytest.raises(TypeError, match=r"blocks must be a sequence of planning\.Block"):
        planning.World(ur3, planning.sphere_model(ur3), table, 5)
    assert "x must be a number in metres; got True" in str(
        planning.validate_goal(world, ("A", True, 0.1))
    )
    with pytest.raises(ValueError, match="plan=True plans from q_start"):
        planning.validate_goal(world, ("A", 0.25, -0.15), plan=True)
