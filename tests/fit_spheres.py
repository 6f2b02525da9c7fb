"""Fit the sphere models of ``urkin.planning`` to the ROS-Industrial collision meshes.

    python -m tests.fit_spheres          # prints the table pasted into urkin/planning/_spheres.py

Each link's mesh is put in the DH frame it moves with (URDF chain against ``Rz(π)·fk_frames``).
Its triangles are split until no edge is longer than 12 mm; the pieces are grouped by k-means
on their centroids (area-weighted, farthest-point start, seeded); each group gets the smallest
sphere the Bădoiu–Clarkson iteration finds around every vertex of its pieces, and its radius is
then the largest distance to those vertices plus 0.5 mm.  A sphere that holds the three vertices
of a triangle holds the whole triangle (a ball is convex), so the spheres cover every point of
the mesh surface by construction; ``tests/test_planning_spheres.py`` checks it on points
sampled afresh, with the spheres placed by urkin and the meshes by the URDF.  A link gets the
fewest spheres (at most 12) whose radii are all within 1.35 times its thickness (the second
largest extent of its vertices along their principal axes) halved: long links get a row of
spheres along their length, compact joint housings one or a few.
"""

from __future__ import annotations

import numpy as np

import urkin

from .robot_models import posed_meshes

MAX_EDGE = 0.012
MARGIN = 0.0005
CAP = 1.35


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


def fit_link(triangles: np.ndarray, k: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
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
    spheres = [enclosing(pieces[label == j].reshape(-1, 3)) for j in range(k) if np.any(label == j)]
    return np.array([c for c, _ in spheres]), np.array([r for _, r in spheres]) + MARGIN


def fit(name: str, max_spheres: int = 12) -> list[tuple[int, np.ndarray, float]]:
    rows = []
    for frame, triangles in enumerate(mesh_in_dh_frames(name)):
        vertices = triangles.reshape(-1, 3)
        centred = vertices - vertices.mean(axis=0)
        axes = np.linalg.svd(centred, full_matrices=False)[2]
        extents = np.sort(np.ptp(centred @ axes.T, axis=0))[::-1]
        cap = CAP * extents[1] / 2  # the link's thickness, as a radius, with room
        for k in range(1, max_spheres + 1):
            c, r = fit_link(triangles, k)
            if r.max() <= cap:
                break
        rows.extend((frame, centre, radius) for centre, radius in zip(c, r))
    return rows


def main() -> None:
    for name in ("ur3", "ur5", "ur10"):
        rows = fit(name)
        print(f'    "{name}": (  # {len(rows)} spheres')
        for frame, centre, radius in rows:
            x, y, z = (round(float(v), 4) + 0.0 for v in centre)
            print(f"        ({frame}, {x:.4f}, {y:.4f}, {z:.4f}, {radius + 5e-5:.4f}),")
        print("    ),")


if __name__ == "__main__":
    main()
