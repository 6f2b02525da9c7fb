"""Tabulate the distance between pairs of links' collision meshes over the two joints between.

    python -m tests.pair_tables     # writes urkin/planning/_pair_tables.py (needs coal)

Three pairs of links sit so close in folded configurations that their covering spheres, which
reach 1–3 cm beyond the meshes, overlap where the meshes are clear:

- the base (DH frame 0) and the upper arm (frame 2), whose relative pose ``A_1(q1) A_2(q2)``
  depends on joints 1 and 2;
- the forearm (frame 3) and wrist 2 (frame 5): ``A_4(q4) A_5(q5)``, joints 4 and 5;
- the forearm and wrist 3 (frame 6), whose pose also depends on joint 6, about which wrist 3
  is nearly round: the table holds the forearm's distance to wrist 3 *turned about joint 6's
  axis by any angle* (a solid of revolution around the mesh, below), so it depends on joints
  4 and 5 only and bounds the distance at every joint 6.

Of random UR5 configurations, the spheres leave 34 % free of self-collision and the forearm
and wrist 2's table 45 %; 138 of VAMP's 700 MotionBenchMaker UR5 problems start or end in such
a sphere overlap with those meshes 1–16 mm apart, and 8 more with the base and upper arm or the
forearm and wrist 3 (1–22 mm apart).  This script measures the exact distance (coal's BVH
distance, triangles against triangles; 0 where they intersect) at every node of a grid of
``N × N`` values of the two joints over a full turn each, rounds it down to ``UNIT``, and caps
it at ``CAP`` (farther is free whatever the joints between nodes do).  It also stores, per
joint, the largest distance of a vertex of the second link from that joint's axis: the speed
bound with which :mod:`urkin.planning.spheres` turns node values into a lower bound of the
distance anywhere between nodes.  ``tests/test_planning_spheres.py`` holds each table to
surface samples of the meshes placed by the URDF at fresh configurations.

The UR5's wrist 3 is round but for a bump 5.6 mm high, 11° wide: revolved, the bump would make a
ring that touches the forearm where the real wrist is millimetres clear (one of
MotionBenchMaker's goals, 5 mm apart, was refused so).  So the mesh, split until no edge is
longer than ``EDGE``, is first cut in two: the pieces with a vertex more than ``BUMP`` farther
from the axis than the wrist's typical radius at that height (in slabs ``EDGE`` thick, the
median over ``SECTORS`` sectors of the turn of each sector's largest radius; the largest of that
in the vertex's slab and its two neighbours) are the bump, when one sphere (made as the fitted
spheres are) of radius at most ``BUMP_RADIUS`` holds them; the table holds the rest, and the
sphere is stored with the table (``<arm>_36_spheres``): a fitted model tests it against the
forearm spheres it can meet.  The UR3's wrist has wider irregularities around a third of its
turn (no small sphere holds them) and the UR10's none: their tables hold the whole wrist.

The solid of revolution around wrist 3: its pieces but for a bump, in slabs ``SLAB`` thick
along joint 6's axis; each slab's radius is the largest distance from
the axis of a vertex within ``EDGE`` of the slab, plus ``EDGE`` (every surface point is within
``EDGE`` of a vertex), drawn as a prism of ``SIDES`` faces circumscribing that circle, with
discs closing the steps between slabs and the ends.
"""

from __future__ import annotations

import base64
import io
import itertools
from pathlib import Path

import numpy as np

import urkin
from urkin.kinematics import dh_transform

from .fit_spheres import mesh_in_dh_frames, sphere_of, subdivide

N = 360  # grid nodes per joint turn: one per degree
UNIT = 0.00025  # m: distances are stored as whole multiples of this, rounded down
CAP = 0.06  # m: distances beyond this are stored as this
#: The pairs of links tabulated (DH frames); a second frame three after the first is turned
#: about its joint's axis (a solid of revolution).
LINKS = ((0, 2), (3, 5), (3, 6))
EDGE, SLAB, SIDES = 0.002, 0.002, 64
#: A bump on wrist 3 (below): mesh reaching more than ``BUMP`` beyond the typical radius of its
#: height, split off when one sphere of radius at most ``BUMP_RADIUS`` holds it.
BUMP, BUMP_RADIUS, SECTORS = 0.002, 0.01, 16
OUT = Path(__file__).resolve().parents[1] / "urkin" / "planning" / "_pair_tables.py"


def bvh(coal, triangles: np.ndarray):
    model = coal.BVHModelOBBRSS()
    vertices = triangles.reshape(-1, 3)
    model.beginModel(len(triangles), len(vertices))
    model.addVertices(vertices)
    model.addTriangles(np.arange(len(vertices)).reshape(-1, 3))
    model.endModel()
    return model


def split(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Wrist 3's mesh (in its DH frame) split until no edge is longer than ``EDGE``, and which
    of the pieces are a bump (see the module notes): pieces (M, 3, 3), bump (M,) bool (all
    False when the mesh has no bump one small sphere holds)."""
    pieces = subdivide(triangles, EDGE)
    v = pieces.reshape(-1, 3)
    r, z = np.hypot(v[:, 0], v[:, 1]), v[:, 2]
    sector = ((np.arctan2(v[:, 1], v[:, 0]) + np.pi) * (SECTORS / (2 * np.pi))).astype(int)
    slab = ((z - z.min()) / EDGE).astype(int)
    outline = np.zeros((slab.max() + 1, SECTORS))  # the largest radius per slab and sector
    np.maximum.at(outline, (slab, sector % SECTORS), r)
    typical = np.pad(np.median(outline, axis=1), 1, mode="edge")
    typical = np.max([typical[slab], typical[slab + 1], typical[slab + 2]], axis=0)
    bump = np.any((r > typical + BUMP).reshape(-1, 3), axis=1)
    if bump.any() and bump_sphere(pieces[bump])[3] > BUMP_RADIUS:
        bump[:] = False  # not a bump but a side of the link: the solid holds it
    return pieces, bump


def bump_sphere(pieces: np.ndarray) -> np.ndarray:
    """The sphere (x, y, z, radius) holding a bump's pieces (as the fitted spheres are made)."""
    centre, radius = sphere_of(pieces)
    return np.array([*centre, radius])


def revolved(triangles: np.ndarray) -> np.ndarray:
    """A closed surface of revolution about z holding ``triangles`` turned by any angle (see
    the module notes): (M, 3, 3)."""
    vertices = subdivide(triangles, EDGE).reshape(-1, 3)
    r, z = np.hypot(vertices[:, 0], vertices[:, 1]), vertices[:, 2]
    edges = np.arange(z.min() - EDGE, z.max() + EDGE + SLAB, SLAB)
    radii = np.array(
        [
            r[(z >= lo - EDGE) & (z <= hi + EDGE)].max(initial=0.0) + EDGE
            for lo, hi in itertools.pairwise(edges)
        ]
    ) / np.cos(np.pi / SIDES)
    angle = np.arange(SIDES + 1) * (2 * np.pi / SIDES)
    ring = np.column_stack([np.cos(angle), np.sin(angle)])  # (SIDES + 1, 2), closed

    def at(radius: float, height: float) -> np.ndarray:
        return np.column_stack([radius * ring, np.full(len(ring), height)])

    out = []

    def annulus(a: float, b: float, height: float) -> None:  # a disc when one radius is 0
        inner, outer = at(min(a, b), height), at(max(a, b), height)
        for m in range(SIDES):
            out.extend([(inner[m], outer[m], outer[m + 1]), (inner[m], outer[m + 1], inner[m + 1])])

    for k, radius in enumerate(radii):
        lo, hi = at(radius, edges[k]), at(radius, edges[k + 1])
        for m in range(SIDES):  # the prism's side
            out.extend([(lo[m], lo[m + 1], hi[m + 1]), (lo[m], hi[m + 1], hi[m])])
        annulus(radii[k - 1] if k else 0.0, radius, edges[k])  # the step below the slab
    annulus(radii[-1], 0.0, edges[-1])  # the top
    return np.array(out)


def table(name: str, first: int, second: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distance table of links ``first`` and ``second`` (DH frames) of arm ``name``, over
    joints ``first + 1`` and ``first + 2``, the second link's reach from those joints' axes,
    and the spheres (k, 4) that hold what the table leaves out (a bump of wrist 3)."""
    import coal

    arm = urkin.robot(name)
    dh = arm.dh_table()
    meshes = mesh_in_dh_frames(name)
    near, far = meshes[first], meshes[second]
    spheres = np.zeros((0, 4))
    if second == first + 3:  # turned about the last joint's axis: in the frame before it
        pieces, bump = split(far)
        if bump.any():
            spheres = bump_sphere(pieces[bump])[None]
        A = dh_transform(0.0, dh[second - 1, 0], dh[second - 1, 1], dh[second - 1, 2])
        far = revolved(pieces[~bump]) @ A[:3, :3].T + A[:3, 3]
    a = coal.CollisionObject(bvh(coal, near), coal.Transform3s())
    b = coal.CollisionObject(bvh(coal, far), coal.Transform3s())
    request, result = coal.DistanceRequest(), coal.DistanceResult()
    hit_request, hit_result = coal.CollisionRequest(), coal.CollisionResult()
    angles = np.arange(N) * (2 * np.pi / N) - np.pi
    A1 = dh_transform(angles, dh[first, 0], dh[first, 1], dh[first, 2])
    A2 = dh_transform(angles, dh[first + 1, 0], dh[first + 1, 1], dh[first + 1, 2])
    out = np.empty((N, N))
    for i in range(N):
        for j in range(N):
            T = A1[i] @ A2[j]
            b.setTransform(coal.Transform3s(T[:3, :3], T[:3, 3]))
            result.clear()
            hit_result.clear()
            if coal.collide(a, b, hit_request, hit_result):
                out[i, j] = 0.0
                continue
            coal.distance(a, b, request, result)
            out[i, j] = max(result.min_distance, 0.0)
    # speed bounds: a vertex's distance from the second joint's axis is fixed; from the
    # first's it depends on the second joint: the largest over the grid
    vertices = far.reshape(-1, 3)
    moved = A2[:, :3, :3] @ vertices.T + A2[:, :3, 3:4]  # (N, 3, V) in frame first + 1
    reach2 = float(np.hypot(moved[:, 0], moved[:, 1]).max())
    placed = A1[0, :3, :3] @ moved + A1[0, :3, 3:4]  # frame first (the first joint's turn
    reach1 = float(np.hypot(placed[:, 0], placed[:, 1]).max())  # does not change it)
    stored = np.floor(np.minimum(out, CAP) / UNIT).astype(np.uint8)
    return stored, np.array([reach1, reach2]), spheres


def main() -> None:
    arrays = {}
    for name in ("ur3", "ur5", "ur10"):
        for first, second in LINKS:
            stored, reach, spheres = table(name, first, second)
            key = f"{name}_{first}{second}"
            arrays[f"{key}_distance"] = stored
            arrays[f"{key}_reach"] = reach
            arrays[f"{key}_spheres"] = spheres
            print(f"{key}: touching at {np.mean(stored == 0):.1%} of the nodes; reach {reach}")
    buffer = io.BytesIO()
    np.savez_compressed(buffer, unit=UNIT, links=np.array(LINKS), **arrays)
    text = base64.b64encode(buffer.getvalue()).decode()
    lines = [f'    b"{text[k : k + 88]}"' for k in range(0, len(text), 88)]
    OUT.write_text(HEADER + "NPZ = (\n" + "\n".join(lines) + "\n)\n", encoding="utf-8")
    print(f"wrote {OUT} ({OUT.stat().st_size:,d} bytes)")


HEADER = '''"""Pairs of links' collision meshes: their distance over the two joints between them.

Written by ``python -m tests.pair_tables`` (see it for the method, and
:class:`urkin.planning.spheres.MeshPair` for the use); do not edit by hand.  ``NPZ`` is a
compressed numpy archive, base64-encoded (a module, so that every copy of the package has
it): ``unit`` (m), ``links`` (k, 2) the pairs' DH frames and, per arm and pair,
``<arm>_<a><b>_distance`` (N, N) in units of ``unit``, ``<arm>_<a><b>_reach`` (2,) in
metres and ``<arm>_<a><b>_spheres`` (k, 4), spheres ``(x, y, z, radius)`` in frame ``b`` (m)
holding the part of link ``b`` the table leaves out.
"""

'''


if __name__ == "__main__":
    main()
