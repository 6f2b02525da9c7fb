"""Fit the sphere models of ``urkin.planning`` to the ROS-Industrial collision meshes.

    python -m tests.fit_spheres          # prints urkin/planning/_sphere_tables.py (needs scipy)

Each link's mesh is put in the DH frame it moves with (URDF chain against ``Rz(π)·fk_frames``).
Its triangles are split until no edge is longer than 12 mm; the pieces are grouped by k-means
on their centroids (area-weighted, farthest-point start, seeded); each group gets the smallest
sphere the Bădoiu–Clarkson iteration finds around every vertex of its pieces, and its radius is
then the largest distance to those vertices plus 0.5 mm.  A sphere that holds the three vertices
of a triangle holds the whole triangle (a ball is convex), so the spheres cover every point of
the mesh surface by construction; ``tests/test_planning_spheres.py`` checks it on points
sampled afresh, with the spheres placed by urkin and the meshes by the URDF.  A link gets the
fewest spheres (at most 12) such that each sphere's radius is within 1.35 times half its own
group's thickness (the second largest extent of the group's vertices along their principal
axes): a tube gets a row of spheres hardly wider than the tube, a compact housing one or two.

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

from .robot_models import posed_meshes, sample_surface

MAX_EDGE = 0.012
MARGIN = 0.0005
CAP = 1.35
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


def fit_link(
    triangles: np.ndarray, k: int, seed: int = 0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    pieces = subdivide(triangles, MAX_EDGE)
    centroid = pieces.mean(axis=1)
    area = 0.5 * np.linalg.norm(
        np.cross(pieces[:, 1] - pieces[:, 0], pieces[:, 2] - pieces[:, 0]), axis=1
    )
    rng = np.random.default_rng(seed)
    sample = rng.choice(len(centroid), size=min(3000, len(centroid)), replace=False)
    points, weights = centroid[sample], area[sample]
    centres = [points[rng.integers(len(points))]]
    for _ in range(k - 1):
        d = np.min(np.linalg.norm(points[:, None] - np.array(centres)[None], axis=2), axis=1)
        centres.append(points[np.argmax(d)])
    centres = np.array(centres)
    for _ in range(60):
        label = np.argmin(np.linalg.norm(points[:, None] - centres[None], axis=2), axis=1)
        new = np.array(
            [
                np.average(points[label == j], axis=0, weights=weights[label == j] + 1e-12)
                if np.any(label == j)
                else centres[j]
                for j in range(k)
            ]
        )
        if np.allclose(new, centres, atol=1e-7):
            break
        centres = new
    label = np.argmin(np.linalg.norm(centroid[:, None] - centres[None], axis=2), axis=1)
    groups = [pieces[label == j].reshape(-1, 3) for j in range(k) if np.any(label == j)]
    spheres = [enclosing(vertices) for vertices in groups]
    return (
        np.array([c for c, _ in spheres]),
        np.array([r for _, r in spheres]) + MARGIN,
        np.array([thickness(vertices) for vertices in groups]),
    )


def thickness(vertices: np.ndarray) -> float:
    """The second largest extent of ``vertices`` along their principal axes."""
    centred = vertices - vertices.mean(axis=0)
    axes = np.linalg.svd(centred, full_matrices=False)[2]
    return float(np.sort(np.ptp(centred @ axes.T, axis=0))[-2])


def fit(name: str, max_spheres: int = 12) -> list[tuple[int, np.ndarray, float]]:
    rows = []
    for frame, triangles in enumerate(mesh_in_dh_frames(name)):
        for k in range(1, max_spheres + 1):
            c, r, t = fit_link(triangles, k)
            if np.all(r <= CAP * t / 2):
                break
        rows.extend((frame, centre, radius) for centre, radius in zip(c, r))
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


def main() -> None:
    print(HEADER, end="")
    print("FITTED = {")
    pairs = {}
    for name in ("ur3", "ur5", "ur10"):
        rows = [(f, c, round(r + 5e-5, 4)) for f, c, r in fit(name)]
        rows = [(f, np.round(c, 4) + 0.0, r) for f, c, r in rows]
        pairs[name] = witnessed_pairs(name, rows)
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
