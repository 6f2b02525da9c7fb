"""Fit the sphere models of ``urkin.planning`` to the ROS-Industrial collision meshes.

    python -m tests.fit_spheres > urkin/planning/_sphere_tables.py   # needs scipy; ~55 min
    ruff format urkin/planning/_sphere_tables.py

Each link's mesh is put in the DH frame it moves with (URDF chain against ``Rz(π)·fk_frames``).
Its triangles are split until no edge is longer than 12 mm, and the pieces are split into groups
by halving: each group gets the smallest sphere the Bădoiu–Clarkson iteration finds around every
vertex of its pieces (its radius then the largest distance to those vertices plus 0.5 mm).  A
sphere that holds the three vertices of a triangle holds the whole triangle (a ball is convex),
so the spheres cover every point of the mesh surface by construction;
``tests/test_planning_spheres.py`` checks it on points sampled afresh, with the spheres placed by
urkin and the meshes by the URDF.  How far a sphere reaches beyond its link is measured at 1,500
points of its surface: from each, the distance to the nearest of 100,000 surface samples of the
link, counted where the point lies outside (on the side the sample's outward normal points to);
the mean over the points is the sphere's *excess*.  A group whose sphere's excess is above 6 mm is
cut in two by a plane across one of its principal axes (at 30 … 70 % of its extent), the cut
whose larger excess is smallest, when that is below 0.8 of the group's own; the halves are
treated alike.  A tube is so cut into slices whose spheres are hardly wider than the tube, a
compact housing into a few pieces; a flat face, which every ball covering it overshoots, stops
the cutting once cuts stop paying.  (Grouping by k-means, which splits a tube's ring before its
length, left spheres reaching 10–25 mm beyond the UR5's forearm and wrists, in the way of 15 of
MotionBenchMaker's 700 start and goal configurations; these spheres, 2.)  A sphere the mean
leaves alone can still reach far past its link over part of its surface (a tube's slice across a
flange): where the 95th percentile of its surface's distances outside the link (its *reach*) is
above 10 mm, it is cut the same way by its reach, and its halves by theirs, while a cut brings
that below 0.8 of it.  (Without this rule a UR5 forearm sphere reached 9 mm past the mesh and
refused MotionBenchMaker's cage goal 100, whose mesh clears a bar by 8 mm.)

Self-collision pairs are witnessed by the meshes (MoveIt's setup assistant samples the same
way, per link): in 2,000 seeded random configurations, wherever two non-adjacent links' meshes
come within 5 mm of each other (surface samples, 3,000 per link), the pair of spheres that hold
the two nearby points is a pair to check.  Pairs that overlap in every one of 20,000 random
configurations are then dropped (a fixed overlap of two housings would make every
configuration a collision).  The test checks on fresh configurations that no mesh contact is
missed.
"""

from __future__ import annotations

import numpy as np

import urkin
from urkin.planning.spheres import SphereModel
from urkin.robots import random_configurations

from .robot_models import posed_meshes, sample_surface, sample_surface_picks

MAX_EDGE = 0.012
MARGIN = 0.0005
EXCESS, GAIN = 0.006, 0.8
REACH_QUANTILE, REACH = 0.95, 0.010
SURFACE_SAMPLES, SPHERE_SAMPLES = 100_000, 1500
WITNESS_CONFIGURATIONS, WITNESS_DISTANCE, WITNESS_POINTS = 2000, 0.005, 3000


def mesh_in_dh_frames(name: str) -> list[np.ndarray]:
    arm = urkin.robot(name)
    q = np.zeros(6)
    frames = urkin.T_BASE_LINK_BASE @ urkin.fk_frames(arm, q)
    out = []
    for k, triangles in enumerate(posed_meshes(name, q)):
        T = np.linalg.inv(frames[k])
        out.append(triangles @ T[:3, :3].T + T[:3, 3])
    return out


def subdivide(triangles: np.ndarray, max_edge: float) -> np.ndarray:
    """Split every triangle into four (edge midpoints) until no edge exceeds ``max_edge``."""
    done = []
    while len(triangles):
        edges = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2).max(axis=1)
        small = edges <= max_edge
        done.append(triangles[small])
        big = triangles[~small]
        a, b, c = big[:, 0], big[:, 1], big[:, 2]
        ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
        triangles = np.concatenate(
            [np.stack(t, axis=1) for t in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))]
        )
    return np.concatenate(done)


def enclosing(points: np.ndarray, iterations: int = 300) -> tuple[np.ndarray, float]:
    """A small sphere around ``points`` (Bădoiu–Clarkson), radius exact for its centre."""
    c = points.mean(axis=0)
    for i in range(1, iterations + 1):
        far = points[np.argmax(np.sum((points - c) ** 2, axis=1))]
        c = c + (far - c) / (i + 1)
    return c, float(np.sqrt(np.max(np.sum((points - c) ** 2, axis=1))))


class Excess:
    """How far spheres reach beyond a link's surface (module notes), from seeded samples."""

    def __init__(self, triangles: np.ndarray, seed: int = 0) -> None:
        from scipy.spatial import cKDTree  # a developer tool: the tests never run the fit

        rng = np.random.default_rng(seed)
        self.points, pick = sample_surface_picks(triangles, SURFACE_SAMPLES, rng)
        a, b, c = triangles[pick, 0], triangles[pick, 1], triangles[pick, 2]
        normal = np.cross(b - a, c - a)
        self.normals = normal / np.maximum(np.linalg.norm(normal, axis=1), 1e-30)[:, None]
        if np.mean(np.sum((self.points - self.points.mean(axis=0)) * self.normals, axis=1)) < 0:
            self.normals = -self.normals  # outward
        self.tree = cKDTree(self.points)
        u = rng.normal(size=(SPHERE_SAMPLES, 3))
        self.directions = u / np.linalg.norm(u, axis=1)[:, None]

    def __call__(self, centre: np.ndarray, radius: float) -> float:
        return float(np.mean(self.beyond(centre, radius)))

    def reach(self, centre: np.ndarray, radius: float) -> float:
        """How far the sphere reaches beyond the link in most directions: the REACH_QUANTILE
        quantile of its surface points' distances outside (module notes)."""
        return float(np.quantile(self.beyond(centre, radius), REACH_QUANTILE))

    def beyond(self, centre: np.ndarray, radius: float) -> np.ndarray:
        """Each sampled point of the sphere's surface: its distance outside the link, or 0."""
        q = centre + radius * self.directions
        d, k = self.tree.query(q)
        outside = np.sum((q - self.points[k]) * self.normals[k], axis=1) > 0
        return np.where(outside, d, 0.0)


def sphere_of(group: np.ndarray) -> tuple[np.ndarray, float]:
    """The sphere of a group of triangle pieces (module notes)."""
    centre, radius = enclosing(group.reshape(-1, 3))
    return centre, radius + MARGIN


def cuts(group: np.ndarray):
    """The candidate halvings of a group: across each principal axis at 30 … 70 %."""
    vertices = group.reshape(-1, 3)
    axes = np.linalg.svd(vertices - vertices.mean(axis=0), full_matrices=False)[2]
    centroids = group.mean(axis=1)
    for axis in axes:
        s = centroids @ axis
        for fraction in (0.3, 0.4, 0.5, 0.6, 0.7):
            at = s.min() + fraction * (s.max() - s.min())
            low, high = group[s <= at], group[s > at]
            if len(low) >= 4 and len(high) >= 4:
                yield low, high


def fit_link(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The spheres (centres (K, 3), radii (K,)) of one link's mesh (module notes): groups cut
    by their mean excess, then the spheres that reach far in many directions cut further by
    their reach."""
    excess = Excess(triangles)
    done, todo = [], [(subdivide(triangles, MAX_EDGE), False)]
    while todo:
        group, by_reach = todo.pop()
        halves = None if by_reach else _cut(group, excess, EXCESS)
        if halves is None:  # done by the mean (or cut by reach already): its reach decides
            by_reach = True
            halves = _cut(group, excess.reach, REACH)
        if halves is None:
            done.append(sphere_of(group))
        else:
            todo += [(half, by_reach) for half in halves]
    return np.array([c for c, _ in done]), np.array([r for _, r in done])


def _cut(group: np.ndarray, measure, limit: float):
    """The two halves of ``group`` whose larger ``measure`` is smallest, when the group's own
    is above ``limit`` and that cut brings it below GAIN of it; else None."""
    own = measure(*sphere_of(group))
    if own <= limit:
        return None
    best = None
    for low, high in cuts(group):
        worst = max(measure(*sphere_of(low)), measure(*sphere_of(high)))
        if best is None or worst < best[0]:
            best = (worst, low, high)
    if best is None or best[0] > GAIN * own:
        return None
    return best[1], best[2]


def fit(name: str) -> list[tuple[int, np.ndarray, float]]:
    rows = []
    for frame, triangles in enumerate(mesh_in_dh_frames(name)):
        centres, radii = fit_link(triangles)
        rows.extend((frame, centre, radius) for centre, radius in zip(centres, radii))
    return rows


def witnesses(name: str, seed: int = 1) -> list[tuple[int, int, np.ndarray, np.ndarray]]:
    """Where non-adjacent links' meshes come within WITNESS_DISTANCE, in random configurations:
    ``(link a, link b, points of a, points of b)``, each in its link's DH frame."""
    from scipy.spatial import cKDTree  # a developer tool: the tests never run the fit

    arm = urkin.robot(name)
    rng = np.random.default_rng(seed)
    found = []
    for n, q in enumerate(random_configurations(arm, WITNESS_CONFIGURATIONS, rng)):
        inverse = np.linalg.inv(urkin.T_BASE_LINK_BASE @ urkin.fk_frames(arm, q))
        points = [
            sample_surface(mesh, WITNESS_POINTS, np.random.default_rng([seed, n, k]))
            for k, mesh in enumerate(posed_meshes(name, q))
        ]
        trees = [cKDTree(p) for p in points]
        for a in range(7):
            for b in range(a + 2, 7):
                d, index = trees[a].query(points[b], distance_upper_bound=WITNESS_DISTANCE)
                near = np.isfinite(d)
                if near.any():
                    pa, pb = points[a][index[near]], points[b][near]
                    found.append(
                        (
                            a,
                            b,
                            pa @ inverse[a][:3, :3].T + inverse[a][:3, 3],
                            pb @ inverse[b][:3, :3].T + inverse[b][:3, 3],
                        )
                    )
    return found


def witnessed_pairs(name: str, rows) -> list[tuple[int, int]]:
    """The sphere pairs that hold a witness, minus those overlapping in every configuration."""
    frames = np.array([frame for frame, _, _ in rows])
    centres = np.array([centre for _, centre, _ in rows])
    radii = np.array([radius for _, _, radius in rows])
    held = np.zeros((len(rows), len(rows)), dtype=bool)
    for a, b, pa, pb in witnesses(name):
        inside_a = np.linalg.norm(pa[:, None] - centres[None], axis=2) <= radii
        inside_b = np.linalg.norm(pb[:, None] - centres[None], axis=2) <= radii
        inside_a &= frames == a
        inside_b &= frames == b
        held |= (inside_a[:, :, None] & inside_b[:, None, :]).any(axis=0)
    i, j = np.nonzero(np.triu(held | held.T, k=1))
    arm = urkin.robot(name)
    model = SphereModel.from_rows(arm, np.column_stack([frames, centres, radii]), pairs=[])
    rng = np.random.default_rng(0)
    W = model.place(random_configurations(arm, 20_000, rng))
    gap = np.linalg.norm(W[:, i] - W[:, j], axis=-1) - radii[i] - radii[j]
    apart = np.any(gap > 0, axis=0)
    return [(int(x), int(y)) for x, y in zip(i[apart], j[apart])]


def fitted(name: str) -> tuple[list, list[tuple[int, int]]]:
    """An arm's rounded rows and their witnessed pairs."""
    rows = [(f, np.round(c, 4) + 0.0, round(r + 5e-5, 4)) for f, c, r in fit(name)]
    return rows, witnessed_pairs(name, rows)


def main() -> None:
    from concurrent.futures import ProcessPoolExecutor

    names = ("ur3", "ur5", "ur10")
    with ProcessPoolExecutor(max_workers=2) as pool:
        results = dict(zip(names, pool.map(fitted, names)))
    print(HEADER, end="")
    print("FITTED = {")
    pairs = {}
    for name, (rows, found) in results.items():
        pairs[name] = found
        print(f'    "{name}": (  # {len(rows)} spheres')
        for frame, (x, y, z), radius in rows:
            print(f"        ({frame}, {x:.4f}, {y:.4f}, {z:.4f}, {radius:.4f}),")
        print("    ),")
    print("}")
    print("PAIRS = {")
    for name, found in pairs.items():
        print(f'    "{name}": (  # {len(found)} pairs')
        for k in range(0, len(found), 8):
            print("        " + " ".join(f"({i}, {j})," for i, j in found[k : k + 8]))
        print("    ),")
    print("}")


HEADER = '''"""The fitted sphere models, one row per sphere: ``(frame, x, y, z, radius)`` in
metres, the centre in DH frame ``frame`` (0 the base … 6 the flange); and the self-collision
pairs the meshes witnessed (sphere indices into the rows).

Written by ``python -m tests.fit_spheres`` from the ROS-Industrial collision meshes (see
:mod:`urkin.planning.spheres` for the method and its test); do not edit by hand.
"""

'''


if __name__ == "__main__":
    main()
