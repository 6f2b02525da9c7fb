"""The fitted sphere models cover the ROS-Industrial collision meshes of their arms.

The meshes are placed by the URDF chain (tests/robot_models.py, no urkin) and the spheres by
``SphereModel.place`` (``urkin.fk_frames``), both in ``base_link``, at random configurations;
points are sampled afresh on every link's surface.
"""

import functools

import numpy as np
import pytest

import urkin
from urkin import planning

from .robot_models import posed_meshes, sample_surface


@pytest.mark.parametrize("name", ["UR3", "UR5", "UR10"])
def test_spheres_cover_the_collision_meshes(name):
    arm = urkin.robot(name)
    model = planning.sphere_model(arm)
    rng = np.random.default_rng(12)
    link = np.minimum(model.frames, 6)
    for q in rng.uniform(-np.pi, np.pi, (4, 6)):
        centres = model.place(q) @ urkin.T_BASE_LINK_BASE[:3, :3].T
        for k, triangles in enumerate(posed_meshes(name, q)):
            points = sample_surface(triangles, 4000, rng)
            own = np.abs(link - k) <= 1  # the same or an adjacent link
            outside = (
                np.linalg.norm(points[:, None] - centres[own][None], axis=-1) - model.radii[own]
            ).min(axis=1)
            inside = np.mean(outside <= 0)
            assert inside >= 0.995, f"{name} link {k}: {inside:.2%} of the surface covered"
            assert outside.max() <= 0.005, f"{name} link {k}: sticks out {outside.max():.4f} m"


def test_every_link_has_spheres_and_the_table_is_metres():
    for name in ("UR3", "UR5", "UR10"):
        model = planning.sphere_model(urkin.robot(name))
        assert set(model.frames.tolist()) == set(range(7))
        assert np.all((model.radii > 0.004) & (model.radii < 0.2))  # 4.7 mm: the UR5's bump


def test_models_follow_the_base_and_refuse_other_arms():
    ur5 = urkin.robot("ur5")
    moved = ur5.with_base(urkin.transforms.make_transform(p=[1.0, 2.0, 3.0]))
    q = np.array([0.3, -1.0, 1.2, 0.1, 0.5, -0.4])
    np.testing.assert_allclose(
        planning.sphere_model(moved).place(q),
        planning.sphere_model(ur5).place(q) + np.array([1.0, 2.0, 3.0]),
        atol=1e-12,
    )
    with pytest.raises(ValueError, match="no fitted sphere model for the UR5e"):
        planning.sphere_model(urkin.robot("ur5e"))
    other = urkin.Robot("UR5", 0.1, -0.425, -0.39225, 0.10915, 0.09465, 0.0823)
    with pytest.raises(ValueError, match="DH lengths"):
        planning.sphere_model(other)


def test_hand_built_pairs_follow_the_stated_rule():
    fitted = planning.sphere_model(urkin.robot("ur5"))
    rows = np.column_stack([fitted.frames, fitted.centres, fitted.radii])
    model = planning.SphereModel.from_rows(fitted.robot, rows, pairs="derive")
    link = np.minimum(model.frames, 6)
    i, j = model.pairs.T
    assert np.all(i < j) and np.all(np.abs(link[i] - link[j]) >= 2)
    # every pair the rule drops never comes within 2 cm, or always overlaps, over fresh samples
    Q = urkin.robots.random_configurations(model.robot, 3000, np.random.default_rng(5))
    W = model.place(Q)
    a, b = np.triu_indices(len(model), k=1)
    candidate = np.abs(link[a] - link[b]) >= 2
    kept = {(int(x), int(y)) for x, y in model.pairs}
    dropped = [(x, y) for x, y, c in zip(a, b, candidate) if c and (x, y) not in kept]
    for x, y in dropped:
        gap = np.linalg.norm(W[:, x] - W[:, y], axis=-1) - model.radii[x] - model.radii[y]
        assert gap.min() > 0.0 or gap.max() <= 0.0, (model.names[x], model.names[y])


CONTACT = 0.003  # surface samples closer than this: the meshes touch (samples are ~4 mm apart)


@pytest.mark.parametrize("name", ["UR3", "UR5", "UR10"])
def test_fitted_pairs_miss_no_contact_of_the_meshes(name):
    """Wherever the model calls a random configuration free of self-collision, no two surface
    samples of non-adjacent links are within CONTACT (fresh configurations, not the fit's).

    The configurations compared are those where spheres of two links tested on their spheres
    (not adjacent, not tabulated) come within CONTACT.  Only mesh points within CONTACT of the
    other link's spheres can be within CONTACT of the other link's surface (the spheres cover
    it), so only those are compared, all against all.  Sensitivity: with the sphere pairs
    dropped, it fails for all three arms."""
    model = planning.sphere_model(urkin.robot(name))
    Q = urkin.robots.random_configurations(model.robot, 20_000, np.random.default_rng(21))
    free = planning.is_free(model, planning.Scene(), Q)
    assert free.mean() >= 0.4  # measured: UR3 66 %, UR5 70 %, UR10 81 % (UR5 meshes: 73 %)
    link = np.minimum(model.frames, 6)
    tabulated = {pair.frames for pair in model.meshes}
    # where spheres of two links tested on their spheres come within CONTACT
    a, b = np.triu_indices(len(model), 1)
    sphere_tested = np.array(
        [y - x >= 2 and (x, y) not in tabulated for x, y in zip(link[a], link[b])]
    )
    a, b = a[sphere_tested], b[sphere_tested]
    W = model.place(Q[free])
    gap = np.linalg.norm(W[:, a] - W[:, b], axis=-1) - model.radii[a] - model.radii[b]
    near = Q[free][gap.min(axis=1) <= CONTACT]
    rng = np.random.default_rng(22)
    checked = 0
    for q in near[:60]:
        centres = model.place(q) @ urkin.T_BASE_LINK_BASE[:3, :3].T
        gap = (
            np.linalg.norm(centres[:, None] - centres[None], axis=-1)
            - model.radii[:, None]
            - model.radii[None]
        )
        meshes = None
        for a in range(7):
            for b in range(a + 2, 7):
                if (a, b) in tabulated:
                    continue  # tested on the meshes themselves (the next test)
                if gap[np.ix_(link == a, link == b)].min() > CONTACT:
                    continue  # their spheres are apart: so are their meshes
                if meshes is None:
                    meshes = [sample_surface(m, 3000, rng) for m in posed_meshes(name, q)]
                near = []
                for own, other in ((a, b), (b, a)):
                    points = meshes[own]
                    reach = (
                        np.linalg.norm(points[:, None] - centres[link == other][None], axis=-1)
                        - model.radii[link == other]
                    )
                    near.append(points[reach.min(axis=1) <= CONTACT])
                if len(near[0]) and len(near[1]):
                    gap = closest(near[0], near[1])
                    assert gap >= CONTACT, f"{name} at {q}: links {a}, {b} {gap:.4f} m"
                checked += 1
    assert checked >= 20  # the test looked where spheres of unchecked pairs meet


@pytest.mark.parametrize("links", [(0, 2), (3, 5), (3, 6)], ids=["0-2", "3-5", "3-6"])
@pytest.mark.parametrize("name", ["UR3", "UR5", "UR10"])
def test_tabulated_meshes_are_never_closer_than_their_table_says(name, links):
    """The base and upper arm, the forearm and wrist 2, and the forearm and wrist 3 (turned
    about joint 6 by any angle) are tested on tables of their meshes' distance over two joints
    (tests/pair_tables.py): a table's lower bound between the grid's nodes must not exceed
    the distance of surface samples of the real meshes (which is at least their distance),
    placed by the URDF at fresh configurations, half of them where the table says the meshes
    are within 1 cm; and it must be close to it (a useless bound would be safe too)."""
    model = planning.sphere_model(urkin.robot(name))
    (pair,) = [p for p in model.meshes if p.frames == links]
    on = np.all(np.sort(model.frames[model.pairs], axis=1) == links, axis=1)
    bumps = np.flatnonzero(np.isin(model.radii, pair.spheres[:, 3]) & (model.frames == links[1]))
    assert len(bumps) == len(pair.spheres)  # the pair's own spheres: the only ones tested
    assert not np.any(on & ~np.isin(model.pairs, bumps).any(axis=1))
    rng = np.random.default_rng(31)
    Q = urkin.robots.random_configurations(model.robot, 40_000, rng)
    bound = pair.lower_bound(Q)
    wide = rng.uniform(-2 * np.pi, 2 * np.pi, (20_000, 6))  # the verdict skips clear cells
    np.testing.assert_array_equal(pair.collides(wide), pair.lower_bound(wide) <= 0.0)
    # at the grid's nodes the bound is the tabulated distance, whichever turn names them
    n = len(pair.distance)
    k = rng.integers(0, n, (500, 2))
    nodes = np.zeros((500, 6))
    joints = slice(pair.joints[0], pair.joints[0] + 2)
    nodes[:, joints] = -np.pi + 2 * np.pi * k / n + 2 * np.pi * rng.integers(-1, 2, (500, 2))
    nodes[:5, joints] = np.pi  # where round-off may land on the far end of the table
    k[:5] = 0
    np.testing.assert_allclose(pair.lower_bound(nodes), pair.distance[k[:, 0], k[:, 1]], atol=1e-9)
    near = np.flatnonzero(bound < 0.01)
    pick = np.concatenate([near[:16], np.flatnonzero(bound >= 0.01)[:16]])
    assert len(near) >= 10
    slack = []
    for q, lower in zip(Q[pick], bound[pick]):
        meshes = posed_meshes(name, q)
        if links == (3, 6):  # the table holds wrist 3 but for its bump (its sphere's, below)
            meshes[6] = tabled_wrist_3(name, meshes[6])
        a, b = (sample_surface(meshes[k], 2500, rng) for k in pair.frames)
        around = np.linalg.norm(np.ptp(b, axis=0)) + 0.06  # b's bounding box and 6 cm
        a = a[np.linalg.norm(a - b.mean(axis=0), axis=1) <= around]
        sampled = closest(a, b) if len(a) else 1.0
        assert lower <= sampled, f"{name} at {q}: table {lower:.4f} m > samples {sampled:.4f} m"
        slack.append(min(sampled, 0.06) - lower)
    # surface samples ~5 mm apart; between nodes 1° apart the bound falls by up to half the
    # slopes (9 mm for the base and the long upper arm); a solid of revolution 2–4 mm wider
    allowed = 0.004 + pair._slope().sum() / 2 + (0.0 if links[1] - links[0] == 2 else 0.004)
    assert np.median(slack) < allowed


@functools.cache
def _wrist_3_split(name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wrist 3's mesh in its DH frame, and its pieces with which of them are its bump
    (``tests.pair_tables.split``), computed once per arm."""
    from tests.fit_spheres import mesh_in_dh_frames
    from tests.pair_tables import split

    local = mesh_in_dh_frames(name)[6]
    return (local, *split(local))


def closest(a: np.ndarray, b: np.ndarray) -> float:
    """The smallest distance between two point sets (n, 3) and (m, 3), from one product:
    ``|a − b|² = |a|² + |b|² − 2 a·b`` (round-off about 1e-16 m² for points within a metre of
    the origin)."""
    d2 = np.einsum("ij,ij->i", a, a)[:, None] + np.einsum("ij,ij->i", b, b)[None] - 2 * a @ b.T
    return float(np.sqrt(max(d2.min(), 0.0)))


def tabled_wrist_3(name: str, posed: np.ndarray, part: bool = False) -> np.ndarray:
    """The pieces of wrist 3's mesh that its table holds (or, ``part=True``, its bump), placed
    like ``posed``, the mesh placed by the URDF: the rigid motion taking the mesh in its DH
    frame onto ``posed``, fitted to their vertices (Kabsch), carries the pieces."""
    local, pieces, bump = _wrist_3_split(name)
    P, W = local.reshape(-1, 3), posed.reshape(-1, 3)
    p0, w0 = P.mean(axis=0), W.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - p0).T @ (W - w0))
    R = (U @ np.diag([1, 1, np.sign(np.linalg.det(U @ Vt))]) @ Vt).T
    np.testing.assert_allclose((P - p0) @ R.T + w0, W, atol=1e-9)
    return (pieces[bump if part else ~bump] - p0) @ R.T + w0


def test_the_ur5s_wrist_3_bump_is_held_by_its_sphere_and_tested_against_the_forearm():
    """The UR5's wrist 3 is round but for a bump 5.6 mm high: its table (forearm and wrist 3)
    holds the solid the rest sweeps about joint 6, and one small sphere, tested against the
    forearm spheres it can meet, holds the bump (placed by the URDF at random configurations).
    The UR3's and UR10's wrists have no bump one small sphere holds: their tables hold all of
    it."""
    model = planning.sphere_model(urkin.robot("UR5"))
    (pair,) = [p for p in model.meshes if p.frames == (3, 6)]
    assert pair.spheres.shape == (1, 4) and pair.spheres[0, 3] < 0.006
    (bump,) = np.flatnonzero(model.radii < 0.006)
    assert model.frames[bump] == 6 and model.names[bump] == "wrist 3 sphere 1"
    mine = model.pairs[np.any(model.pairs == bump, axis=1)]
    assert np.all(mine[:, 1] == bump) and np.all(model.frames[mine[:, 0]] == 3)
    assert len(mine) >= 5  # the forearm spheres it can meet (the rule of hand-built models)
    others = np.setdiff1d(np.flatnonzero(model.frames == 3), mine[:, 0])
    rng = np.random.default_rng(41)
    W = model.place(urkin.robots.random_configurations(model.robot, 5000, rng))
    gap = np.linalg.norm(W[:, others] - W[:, [bump]], axis=-1) - model.radii[others]
    assert gap.min() > model.radii[bump]  # those it is not tested against never touch it
    for q in rng.uniform(-np.pi, np.pi, (5, 6)):
        centre = model.place(q)[bump] @ urkin.T_BASE_LINK_BASE[:3, :3].T
        points = tabled_wrist_3("UR5", posed_meshes("UR5", q)[6], part=True).reshape(-1, 3)
        assert np.linalg.norm(points - centre, axis=1).max() <= model.radii[bump]
    for name in ("UR3", "UR10"):
        meshes = planning.sphere_model(urkin.robot(name)).meshes
        assert [p.spheres.shape for p in meshes if p.frames == (3, 6)] == [(0, 4)]


def test_tool_spheres_join_the_model_with_derived_pairs():
    model = planning.sphere_model(urkin.robot("ur5"))
    gripper = model.with_tool_spheres([[0, 0, 0.06], [0, 0, 0.12]], 0.035, name="block")
    assert len(gripper) == len(model) + 2
    assert gripper.names[-1] == "block sphere 1"
    new = gripper.pairs[~np.isin(gripper.pairs, np.arange(len(model))).all(axis=1)]
    assert len(new) and np.all(np.max(new, axis=1) >= len(model))
    assert np.all(np.minimum(gripper.frames[new.min(axis=1)], 6) <= 4)  # never wrist 2/3


def test_derived_pairs_do_not_depend_on_where_the_arm_stands():
    """The rule's distances are the same wherever the base is: an arm moved and turned gets the
    pairs it gets at the origin, whether derived afresh or found again (the same spheres on
    the same arm and tool)."""
    fitted = planning.sphere_model(urkin.robot("ur3"))
    rows = np.column_stack([fitted.frames, fitted.centres, fitted.radii])
    turn = urkin.transforms.rot_z(2.0) @ urkin.transforms.rot_x(0.1)
    T = urkin.transforms.make_transform(turn, [0.4, -0.3, 0.8])
    here = planning.SphereModel.from_rows(fitted.robot, rows)
    there = planning.SphereModel.from_rows(fitted.robot.with_base(T), rows)
    np.testing.assert_array_equal(here.pairs, there.pairs)
    block = [[0, 0, 0.03], [0, 0.02, 0.05]]
    again = planning.SphereModel(
        fitted.robot.with_base(T),
        *(getattr(fitted, k) for k in ("frames", "centres", "radii")),
        fitted.pairs,
        fitted.names,
        fitted.source,
        fitted.meshes,
    ).with_tool_spheres(block, 0.02)
    np.testing.assert_array_equal(again.pairs, fitted.with_tool_spheres(block, 0.02).pairs)
    assert len(again.pairs) > len(fitted.pairs)
    # the tool is part of the arm: a longer one gives its spheres other pairs
    long = urkin.transforms.make_transform(None, [0, 0, 0.25])
    tooled = planning.SphereModel(
        fitted.robot.with_tool(long),
        *(getattr(fitted, k) for k in ("frames", "centres", "radii", "pairs", "names", "source")),
        fitted.meshes,
    ).with_tool_spheres(block, 0.02)
    assert not np.array_equal(tooled.pairs, again.pairs)


def test_hand_built_models_check_their_rows():
    ur5 = urkin.robot("ur5")
    with pytest.raises(ValueError, match=r"rows must have shape \(S, 5\)"):
        planning.SphereModel.from_rows(ur5, [[1, 0, 0, 0.1]])
    with pytest.raises(ValueError, match=r"rows\[1\]: the frame must be an integer 0 … 7"):
        planning.SphereModel.from_rows(ur5, [[1, 0, 0, 0, 0.1], [8, 0, 0, 0, 0.1]])
    with pytest.raises(ValueError, match=r"rows\[0\]: the radius must be positive"):
        planning.SphereModel.from_rows(ur5, [[1, 0, 0, 0, -0.1]])
    with pytest.raises(ValueError, match="NaN"):
        planning.SphereModel.from_rows(ur5, [[1, 0, 0, np.nan, 0.1]])
    with pytest.raises(ValueError, match="two different spheres"):
        planning.SphereModel.from_rows(ur5, [[1, 0, 0, 0, 0.1], [4, 0, 0, 0, 0.1]], [[0, 5]])
    with pytest.raises(TypeError, match="robot must be a urkin Robot"):
        planning.SphereModel.from_rows("ur5", [[1, 0, 0, 0, 0.1]])
    model = planning.sphere_model(ur5)
    with pytest.raises(ValueError, match=r"centres must have shape \(K, 3\); got shape \(2, 6\)"):
        model.with_tool_spheres(np.zeros((2, 6)), 0.01)  # not silently four centres
    with pytest.raises(ValueError, match=r"radii must be one radius or one per centre \(1\)"):
        model.with_tool_spheres([[0, 0, 0.1]], [0.01, 0.02])
    with pytest.raises(ValueError, match=r"radii\[1\] must be positive and at most 2 m"):
        model.with_tool_spheres([[0, 0, 0.1], [0, 0, 0.2]], [0.01, -0.01])
    with pytest.raises(ValueError, match=r"radii\[0\] must be positive and at most 2 m"):
        model.with_tool_spheres([[0, 0, 0.1]], 100.0)  # not rows[0], which the caller never saw
    with pytest.raises(TypeError, match="name must be a str"):
        model.with_tool_spheres([[0, 0, 0.1]], 0.02, name=3)
    with pytest.raises(ValueError, match=r"pairs must be integer sphere indices of shape \(P, 2\)"):
        planning.SphereModel.from_rows(ur5, [[3, 0, 0, 0, 0.1], [6, 0, 0, 0, 0.1]], [[0, 1], [1]])
    with pytest.raises(TypeError, match=r"boxes\[0\]: .*unexpected keyword argument 'center'"):
        planning.Scene(boxes=[{"center": [0, 0, 0], "size": [1, 1, 1]}])


def test_the_constructor_checks_and_copies_what_it_is_given():
    """SphereModel(...) is public: it checks its fields as from_rows does (naming the sphere)
    and keeps read-only copies, so the caller's arrays stay theirs and cannot change it."""
    ur5 = urkin.robot("ur5")
    frames, centres, radii = np.array([3, 6]), np.zeros((2, 3)), np.array([0.05, 0.04])
    pairs = np.zeros((0, 2), dtype=int)
    model = planning.SphereModel(ur5, frames, centres, radii, pairs, ("a", "b"))
    radii[0] = -1.0  # the caller's array is still writeable, and the model keeps its own
    assert model.radii[0] == 0.05 and not model.radii.flags.writeable
    with pytest.raises(ValueError, match="sphere 0: the radius must be positive"):
        planning.SphereModel(ur5, frames, centres, np.array([-0.1, 0.04]), pairs, ("a", "b"))
    with pytest.raises(ValueError, match="sphere 1: the frame must be an integer"):
        planning.SphereModel(ur5, [3, 9], centres, [0.05, 0.04], pairs, ("a", "b"))
    with pytest.raises(ValueError, match=r"centres and radii must have shapes \(2, 3\)"):
        planning.SphereModel(ur5, [3, 6], [[0, 0, 0]], [0.1], pairs, ("a", "b"))
    with pytest.raises(ValueError, match="two different spheres among 0 … 1"):
        planning.SphereModel(ur5, [3, 6], centres, [0.05, 0.04], [[0, 2]], ("a", "b"))
    with pytest.raises(ValueError, match="names holds 1 labels for 2 spheres"):
        planning.SphereModel(ur5, [3, 6], centres, [0.05, 0.04], pairs, ("a",))
    with pytest.raises(TypeError, match="robot must be a urkin Robot"):
        planning.SphereModel("ur5", [3, 6], centres, [0.05, 0.04], pairs, ("a", "b"))
    with pytest.raises(TypeError, match="meshes must be a tuple"):
        planning.SphereModel(ur5, [3, 6], centres, [0.05, 0.04], pairs, ("a", "b"), "", [1])


def test_mesh_pairs_name_what_is_wrong_with_their_arguments():
    D, reach = np.zeros((4, 4)), np.zeros(2)
    pair = planning.spheres.MeshPair([3, 5], D.tolist(), reach.tolist())  # lists are arrays
    assert pair.frames == (3, 5) and pair.distance.shape == (4, 4) and pair.spheres.shape == (0, 4)
    with pytest.raises(ValueError, match=r"frames must be two DH frame numbers.*got \(3,\)"):
        planning.spheres.MeshPair((3,), D, reach)
    with pytest.raises(ValueError, match="frames must be two DH frame numbers"):
        planning.spheres.MeshPair((3.0, 5.0), D, reach)
    with pytest.raises(TypeError, match="distance must be numbers"):
        planning.spheres.MeshPair((3, 5), "table", reach)
    with pytest.raises(ValueError, match=r"distance must be \(n, n\)"):
        planning.spheres.MeshPair((3, 5), 0.0, reach)
    with pytest.raises(ValueError, match="reach non-negative"):
        planning.spheres.MeshPair((3, 5), D, [0.1, np.nan])
    with pytest.raises(ValueError, match=r"spheres must be finite rows .* got shape \(4,\)"):
        planning.spheres.MeshPair((3, 6), D, reach, [0, 0, 0, 0.01])
    with pytest.raises(ValueError, match="spheres: every radius must be positive"):
        planning.spheres.MeshPair((3, 6), D, reach, [[0, 0, 0, -0.01]])
    with pytest.raises(ValueError, match="spheres must be finite rows"):
        planning.spheres.MeshPair((3, 6), D, reach, [[0, 0, np.inf, 0.01]])


def test_mesh_pairs_refuse_tables_they_cannot_use():
    fine = np.zeros((4, 4)), np.zeros(2)
    for frames in ((3, 4), (2, 6), (4, 7), (5, 7)):  # adjacent, too far apart, past the flange
        with pytest.raises(ValueError, match=r"frames must be \(a, a \+ 2\) or \(a, a \+ 3\)"):
            planning.spheres.MeshPair(frames, *fine)
    assert planning.spheres.MeshPair((3, 6), *fine).joints == (3, 4)  # wrist 3 revolved
    with pytest.raises(ValueError, match=r"distance must be \(n, n\)"):
        planning.spheres.MeshPair((3, 5), np.zeros((4, 3)), np.zeros(2))
    with pytest.raises(ValueError, match="must be finite"):
        planning.spheres.MeshPair((3, 5), np.full((4, 4), np.nan), np.zeros(2))
    # 1 cm between neighbouring nodes of joint 5, where a reach of 0.01 m/rad allows 1.6 cm
    # per step (of π/2) in joint 4 but nothing in joint 5
    steep = np.array([[0.0, 0.01, 0.0, 0.01]] * 4)
    planning.spheres.MeshPair((3, 5), steep.T, np.array([0.01, 0.0]))
    with pytest.raises(ValueError, match="neighbouring nodes of joint 5, more than its reach"):
        planning.spheres.MeshPair((3, 5), steep, np.array([0.01, 0.0]))


@pytest.mark.parametrize("name", ["ur3", "ur5", "ur10"])
def test_table_lower_bounds_fall_no_faster_than_their_reach(rng, name):
    """Between any two configurations, across cells too, a table's lower bound changes by at
    most ``Σ |Δq| · reach``: what lets a grown check stand for every sample near it."""
    for pair in planning.sphere_model(urkin.robot(name)).meshes:
        j = pair.joints[0]
        n = len(pair.distance)
        near = np.argwhere(pair.distance < 0.02)  # where the bound is small and varies most
        Q = rng.uniform(-np.pi, np.pi, (4000, 6))
        Q[:2000, j : j + 2] = -np.pi + 2 * np.pi * near[rng.choice(len(near), 2000)] / n
        step = rng.normal(size=Q.shape) * rng.choice([1e-4, 1e-2, 0.1], (len(Q), 1))
        change = np.abs(pair.lower_bound(Q + step) - pair.lower_bound(Q))
        assert np.all(change <= np.abs(step[:, j : j + 2]) @ pair.reach + 1e-12)


@pytest.mark.parametrize("plain", [False, True], ids=["base and tool", "plain"])
@pytest.mark.parametrize("n", [0, 1, 2, 3, 4, 5, 6, 100, 512, 513, 1500])
def test_check_frames_match_the_frames_of_the_kinematics_at_every_stack_size(rng, n, plain):
    """The collision checks' frames, products of the DH link transforms for mid-sized stacks,
    or the one-pose code written into the stack for a few configurations of a plain arm, are
    the generated kinematics' frames with the tool to round-off, at any stack size (and on a
    moved base with a tool), whichever the checks pick for it."""
    T = urkin.transforms.make_transform(urkin.transforms.rot_z(0.7), [0.2, -0.1, 0.5])
    arm = urkin.robot("ur5") if plain else urkin.robot("ur5").with_base(T).with_tool(T)
    Q = rng.uniform(-np.pi, np.pi, (n, 6))
    generated = planning.spheres.frames_with_tool(arm, Q)
    np.testing.assert_allclose(planning.spheres._chain(arm, Q), generated, atol=1e-14)
    np.testing.assert_allclose(planning.spheres._frames(arm, Q), generated, atol=1e-14)


@pytest.mark.parametrize("n", [1, 31, 32, 600])
def test_every_sphere_placed_at_once_is_where_place_puts_it(rng, n):
    """The checks place every sphere of many configurations frame by frame (one small product
    per frame), of few with the placing matrix: both are ``SphereModel.place``, also for a
    hand-built model whose frames are not in order, with tool spheres."""
    from urkin.planning.checks import _place_all

    arm = urkin.robot("ur3").with_tool(urkin.transforms.make_transform(np.eye(3), [0, 0, 0.1]))
    rows = [(f, *rng.normal(0, 0.1, 3), 0.05) for f in (3, 0, 6, 3, 2, 2, 5, 1, 4)]
    models = [planning.sphere_model(arm), planning.SphereModel.from_rows(arm, rows)]
    models.append(models[1].with_tool_spheres([[0, 0, 0.05], [0.02, 0, 0.1]], [0.03, 0.02]))
    Q = rng.uniform(-np.pi, np.pi, (n, 6))
    for model in models:
        placed = _place_all(model, planning.spheres._frames(arm, Q))  # (n, 3, S)
        expected = model.place(Q)  # (n, S, 3)
        np.testing.assert_allclose(placed.transpose(0, 2, 1), expected, atol=1e-14)


def test_hand_built_models_refuse_far_centres_bad_names_and_bad_sphere_indices():
    arm = urkin.robot("ur5")
    with pytest.raises(ValueError, match="centre must lie within 5 m"):
        planning.SphereModel.from_rows(arm, [[6, 0, 0, 1e300, 0.05]])
    with pytest.raises(ValueError, match="centres must lie within 5 m"):
        planning.sphere_model(arm).with_tool_spheres([[0, 0, 1e6]], 0.05)
    rows = [[6, 0, 0, 0, 0.05], [6, 0, 0, 0.1, 0.05]]
    for names in (5, "ab", [1, 2]):
        with pytest.raises(TypeError, match="names must be a list of strings"):
            planning.SphereModel.from_rows(arm, rows, names=names)
    model = planning.sphere_model(arm)
    for only in ([100], [-1]):
        with pytest.raises(ValueError, match="only must hold sphere indices from 0"):
            planning.self_pairs(model, only=only)
    for only in ([0.9], [True], [[1, 2]]):
        with pytest.raises(ValueError, match="only must be sphere indices"):
            planning.self_pairs(model, only=only)
