"""Tabulate the distance between the forearm's and wrist 2's collision meshes over joints 4, 5.

    python -m tests.pair_tables     # writes urkin/planning/_pair_tables.py (needs coal)

The forearm moves with DH frame 3 and wrist 2 with frame 5, so their relative pose
``T_3_5 = A_4(q4) A_5(q5)`` depends on joints 4 and 5 only.  Their covering spheres reach
2–3 cm beyond the meshes, and near each other that is the whole gap: of random UR5
configurations, the spheres leave 34 % free of self-collision and the table 45 %, and 138 of
VAMP's 700 MotionBenchMaker UR5 problems start or end in such a sphere overlap with the
meshes 1–16 mm apart.  This script measures the meshes' exact distance (coal's BVH distance,
triangles against triangles; 0 where they intersect) at every node of a grid of ``N × N``
values of (q4, q5) over a full turn each, rounds it down to ``UNIT``, and caps it at ``CAP``
(farther is free whatever the joints between nodes do).  It also stores, per joint, the
largest distance of a wrist 2 vertex from that joint's axis: the speed bound with which
:mod:`urkin.planning.spheres` turns node values into a lower bound of the distance anywhere
between nodes.  ``tests/test_planning_spheres.py`` holds the table to surface samples of the
meshes placed by the URDF at fresh configurations.
"""

from __future__ import annotations

import base64
import io
from pathlib import Path

import numpy as np

import urkin
from urkin.kinematics import dh_transform

from .fit_spheres import mesh_in_dh_frames

N = 360  # grid nodes per joint turn: one per degree
UNIT = 0.00025  # m: distances are stored as whole multiples of this, rounded down
CAP = 0.06  # m: distances beyond this are stored as this
FRAMES = (3, 5)  # the forearm and wrist 2
OUT = Path(__file__).resolve().parents[1] / "urkin" / "planning" / "_pair_tables.py"


def bvh(coal, triangles: np.ndarray):
    model = coal.BVHModelOBBRSS()
    vertices = triangles.reshape(-1, 3)
    model.beginModel(len(triangles), len(vertices))
    model.addVertices(vertices)
    model.addTriangles(np.arange(len(vertices)).reshape(-1, 3))
    model.endModel()
    return model


def table(name: str) -> tuple[np.ndarray, np.ndarray]:
    import coal

    arm = urkin.robot(name)
    meshes = mesh_in_dh_frames(name)
    forearm, wrist2 = meshes[FRAMES[0]], meshes[FRAMES[1]]
    a = coal.CollisionObject(bvh(coal, forearm), coal.Transform3s())
    b = coal.CollisionObject(bvh(coal, wrist2), coal.Transform3s())
    request, result = coal.DistanceRequest(), coal.DistanceResult()
    hit_request, hit_result = coal.CollisionRequest(), coal.CollisionResult()
    dh = arm.dh_table()
    angles = np.arange(N) * (2 * np.pi / N) - np.pi
    A4 = dh_transform(angles, dh[3, 0], dh[3, 1], dh[3, 2])
    A5 = dh_transform(angles, dh[4, 0], dh[4, 1], dh[4, 2])
    out = np.empty((N, N))
    for i in range(N):
        for j in range(N):
            T = A4[i] @ A5[j]
            b.setTransform(coal.Transform3s(T[:3, :3], T[:3, 3]))
            result.clear()
            hit_result.clear()
            if coal.collide(a, b, hit_request, hit_result):
                out[i, j] = 0.0
                continue
            coal.distance(a, b, request, result)
            out[i, j] = max(result.min_distance, 0.0)
    # speed bounds: a wrist 2 vertex's distance from joint 5's axis (z4) is fixed; from joint
    # 4's (z3) it depends on q5: the largest over the grid
    vertices = wrist2.reshape(-1, 3)
    A5v = A5[:, :3, :3] @ vertices.T + A5[:, :3, 3:4]  # (N, 3, V) in frame 4
    reach5 = float(np.hypot(A5v[:, 0], A5v[:, 1]).max())
    in3 = A4[0, :3, :3] @ A5v + A4[0, :3, 3:4]  # frame 3 (the distance to z3 ignores q4)
    reach4 = float(np.hypot(in3[:, 0], in3[:, 1]).max())
    stored = np.floor(np.minimum(out, CAP) / UNIT).astype(np.uint8)
    return stored, np.array([reach4, reach5])


def main() -> None:
    arrays = {}
    for name in ("ur3", "ur5", "ur10"):
        stored, reach = table(name)
        arrays[f"{name}_distance"] = stored
        arrays[f"{name}_reach"] = reach
        print(f"{name}: touching at {np.mean(stored == 0):.1%} of the nodes; reach {reach}")
    buffer = io.BytesIO()
    np.savez_compressed(buffer, unit=UNIT, frames=np.array(FRAMES), **arrays)
    text = base64.b64encode(buffer.getvalue()).decode()
    lines = [f'    b"{text[k : k + 88]}"' for k in range(0, len(text), 88)]
    OUT.write_text(HEADER + "NPZ = (\n" + "\n".join(lines) + "\n)\n", encoding="utf-8")
    print(f"wrote {OUT} ({OUT.stat().st_size:,d} bytes)")


HEADER = '''"""The forearm's and wrist 2's collision meshes: their distance over joints 4 and 5.

Written by ``python -m tests.pair_tables`` (see it for the method, and
:class:`urkin.planning.spheres.MeshPair` for the use); do not edit by hand.  ``NPZ`` is a
compressed numpy archive, base64-encoded (a module, so that every copy of the package has
it): ``unit`` (m), ``frames`` and, per arm, ``<arm>_distance`` (N, N) in units of ``unit``
and ``<arm>_reach`` (2,) in metres.
"""

'''


if __name__ == "__main__":
    main()
