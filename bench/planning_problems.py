"""Seeded UR5 planning problems in the style of MotionBenchMaker, for ``bench/planning.py``.

Every scene stands on the floor, a slab whose top is at z = −0.01 m under the arm's base (the
base's own spheres are never tested against the scene).  Five families, each scene's
obstacles jittered from the problem's seed:

* ``empty``: the floor only; start and goal drawn uniformly in a turn of every joint (see
  :data:`CENTRES`) until both are free.  With no obstacle the straight edge between two free
  configurations is free (every draw tried was), so this family is the one exception to the
  rule below: it times the fixed cost of a planning call;
* ``table``: pick and place on the floor around a tall divider and a few small boxes, the
  tool pointing down at both ends;
* ``shelf``: a bookshelf of boxes (back, sides, four shelves) in front of the arm, the tool
  pointing into one compartment (level or tilted down by up to 1 rad) at the start and into
  another at the goal;
* ``box``: an open box on the floor, the goal inside it pointing down, the start beside it;
* ``cage``: vertical bars (cylinders) around the arm tied by two rings of horizontal bars, the
  tool reaching out and down (0.2 to 1.2 rad) through one window at the start and through
  another at the goal.

Tool poses become configurations through the closed-form IK (:func:`urkin.ik_analytic`): the
start is the free solution closest to an elbow-up reference facing the start, the goal the
free solution closest to the start (as a seeded IK would give).  A problem is kept only when
both ends are free (:func:`urkin.planning.is_free`) and the straight edge between them is not
(:func:`urkin.planning.edges_free` at its default 1 cm), so no problem is trivial.  Problem
``(family, k)`` depends only on the family, ``k`` and the base seed: rejected draws are skipped,
the kept ones keep their index as their name.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

import urkin
from urkin import planning

ROBOT = urkin.robot("ur5")
MODEL = planning.sphere_model(ROBOT)
FLOOR = planning.Box([0.0, 0.0, -0.06], [2.5, 2.5, 0.1], name="floor")
FAMILIES = ("empty", "table", "shelf", "box", "cage")
DOWN = np.array([0.0, 0.0, -1.0])


@dataclass(frozen=True)
class Problem:
    """One planning query: a scene, a start and a goal configuration."""

    family: str
    draw: int  # the index of the draw that made it: (family, draw, base seed) rebuild it
    scene: planning.Scene
    start: np.ndarray
    goal: np.ndarray

    @property
    def name(self) -> str:
        return f"{self.family}/{self.draw}"


def rz(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def up(z: float) -> np.ndarray:
    return np.array([0.0, 0.0, z])


def polar(radius: float, angle: float, z: float) -> np.ndarray:
    return np.array([radius * math.cos(angle), radius * math.sin(angle), z])


def pose(position: np.ndarray, approach: np.ndarray, spin: float) -> np.ndarray:
    """A tool pose at ``position`` whose z axis (the flange's approach) is ``approach``,
    turned by ``spin`` about it."""
    z = approach / np.linalg.norm(approach)
    hint = np.array([1.0, 0.0, 0.0]) if abs(z[2]) > 0.9 else np.array([0.0, 0.0, 1.0])
    x = np.cross(hint, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    c, s = math.cos(spin), math.sin(spin)
    T = np.eye(4)
    T[:3, 0], T[:3, 1], T[:3, 2] = c * x + s * y, -s * x + c * y, z
    T[:3, 3] = position
    return T


def wrap(q: np.ndarray) -> np.ndarray:
    return (q + np.pi) % (2 * np.pi) - np.pi


#: The turn each joint is moved into, so that both ends of a problem lie in the same turn of
#: the planners' joint space (limits ±2π, no wrapping): joint 1 about 0 (neither end has to
#: turn through q1 = ±π, where the first fitted UR5 model's base and upper arm met for every
#: q2), joints 2 and 4 about −π/2 (the upper arm above the horizontal, the wrist folded the
#: usual way), joints 3 and 5 about 0; joint 6 to the turn nearest the start.
CENTRES = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])


def canonical(q: np.ndarray, near: np.ndarray | None = None) -> np.ndarray:
    """``q`` moved by whole turns into the turn about :data:`CENTRES` (joint 6: about
    ``near``'s when given), so that the ends of a problem do not sit a turn apart for no
    reason."""
    centres = CENTRES.copy()
    if near is not None:
        centres[5] = near[5]
    return centres + wrap(q - centres)


def free_ik(scene: planning.Scene, T: np.ndarray, near: np.ndarray) -> np.ndarray | None:
    """The collision-free closed-form IK solution of ``T`` closest to ``near``, or None."""
    solutions = urkin.ik_analytic(ROBOT, T)
    if len(solutions) == 0:
        return None
    solutions = solutions[planning.is_free(MODEL, scene, solutions)]
    if len(solutions) == 0:
        return None
    solutions = canonical(solutions)
    return solutions[np.argmin(np.linalg.norm(wrap(solutions - near), axis=1))]


def facing(angle: float) -> np.ndarray:
    """An elbow-up reference configuration with the arm turned towards ``angle`` (at q1 = 0
    the UR arm points along −x)."""
    return np.array([wrap(np.array(angle - np.pi)), -1.3, 1.3, -1.57, -1.57, 0.0])


def tilted(direction: np.ndarray, pitch: float) -> np.ndarray:
    """A horizontal ``direction`` tilted down by ``pitch`` radians."""
    return math.cos(pitch) * direction + math.sin(pitch) * DOWN


PoseSampler = Callable[[np.random.Generator], np.ndarray]


def ends(
    rng: np.random.Generator,
    scene: planning.Scene,
    start_pose: PoseSampler,
    goal_pose: PoseSampler,
    angle: float,
    tries: int = 12,
) -> tuple[np.ndarray, np.ndarray] | None:
    """Start and goal configurations from tool poses drawn until one has a free IK solution
    (``tries`` draws each): the start closest to the elbow-up reference facing ``angle``, the
    goal closest to the start."""
    for _ in range(tries):
        start = free_ik(scene, start_pose(rng), facing(angle))
        if start is not None:
            break
    else:
        return None
    for _ in range(tries):
        goal = free_ik(scene, goal_pose(rng), start)
        if goal is not None:
            return start, canonical(goal, start)
    return None


def box(
    centre: np.ndarray, size: tuple[float, float, float], angle: float, name: str
) -> planning.Box:
    return planning.Box(centre, size, rotation=rz(angle), name=name)


def any_spin(rng: np.random.Generator) -> float:
    return rng.uniform(-np.pi, np.pi)


# --- the families: each draws (scene, start, goal) from a generator, or None to retry --------

Draw = tuple[planning.Scene, np.ndarray, np.ndarray] | None


def empty(rng: np.random.Generator) -> Draw:
    scene = planning.Scene(boxes=[FLOOR])
    Q = canonical(rng.uniform(-np.pi, np.pi, (64, 6)))
    free = Q[planning.is_free(MODEL, scene, Q)]
    if len(free) < 2:
        return None
    return scene, free[0], canonical(free[1], free[0])


def table(rng: np.random.Generator) -> Draw:
    phi_s = rng.uniform(-np.pi, np.pi)
    phi_g = phi_s + rng.choice([-1, 1]) * rng.uniform(1.0, 2.0)
    r_s, r_g = rng.uniform(0.4, 0.65, 2)
    p_s = polar(r_s, phi_s, rng.uniform(0.12, 0.25))
    p_g = polar(r_g, phi_g, rng.uniform(0.08, 0.2))
    mid = 0.5 * (phi_s + phi_g)
    boxes = [
        FLOOR,
        box(
            polar(0.5 * (r_s + r_g) + rng.uniform(-0.05, 0.05), mid, 0.0),
            (rng.uniform(0.35, 0.5), rng.uniform(0.06, 0.12), 2 * rng.uniform(0.3, 0.45)),
            mid,
            "divider",
        ),
    ]
    low, high = min(phi_s, phi_g), max(phi_s, phi_g)
    for k in range(int(rng.integers(3, 6))):
        centre = polar(rng.uniform(0.3, 0.7), rng.uniform(low, high), 0.0)
        if min(np.linalg.norm(centre[:2] - p[:2]) for p in (p_s, p_g)) < 0.15:
            continue  # keep the grasp spots clear
        height = rng.uniform(0.08, 0.25)
        centre[2] = height / 2 - 0.01
        size = (rng.uniform(0.05, 0.1), rng.uniform(0.05, 0.1), height)
        boxes.append(box(centre, size, rng.uniform(0, np.pi), f"object {k}"))
    scene = planning.Scene(boxes=boxes)
    found = ends(
        rng,
        scene,
        lambda r: pose(p_s, DOWN, any_spin(r)),
        lambda r: pose(p_g, DOWN, any_spin(r)),
        phi_s,
    )
    return None if found is None else (scene, *found)


def shelf(rng: np.random.Generator) -> Draw:
    phi = rng.uniform(-np.pi, np.pi)
    front, depth, width = rng.uniform(0.45, 0.6), rng.uniform(0.28, 0.35), rng.uniform(0.8, 1.1)
    levels = np.array([0.25, 0.6, 0.95, 1.25]) + rng.uniform(-0.03, 0.03, 4)
    u = np.array([math.cos(phi), math.sin(phi), 0.0])
    v = np.array([-u[1], u[0], 0.0])
    middle = front + depth / 2
    top = levels[-1]
    boxes = [
        FLOOR,
        box((front + depth + 0.01) * u + up(top / 2), (0.02, width, top), phi, "back"),
        box(middle * u + width / 2 * v + up(top / 2), (depth, 0.02, top), phi, "side 1"),
        box(middle * u - width / 2 * v + up(top / 2), (depth, 0.02, top), phi, "side 2"),
    ]
    boxes += [
        box(middle * u + up(z), (depth, width, 0.02), phi, f"shelf {k}")
        for k, z in enumerate(levels)
    ]
    scene = planning.Scene(boxes=boxes)
    # compartments: floor to shelf 0, shelf 0 to 1, shelf 1 to 2 (the top one is out of reach)
    floors = np.concatenate([[-0.01], levels[:2]])
    a, b = rng.choice(3, 2, replace=False)

    def inside(k: int) -> PoseSampler:
        def sample(r: np.random.Generator) -> np.ndarray:
            z = floors[k] + r.uniform(0.4, 0.6) * (levels[k] - floors[k])
            at = (front + r.uniform(0.0, 0.1)) * u + r.uniform(-0.3, 0.3) * width * v + up(z)
            return pose(at, tilted(u, r.uniform(0.0, 1.0)), any_spin(r))

        return sample

    found = ends(rng, scene, inside(a), inside(b), phi)
    return None if found is None else (scene, *found)


def open_box(rng: np.random.Generator) -> Draw:
    phi = rng.uniform(-np.pi, np.pi)
    distance = rng.uniform(0.45, 0.6)
    sx, sy, h = rng.uniform(0.32, 0.42), rng.uniform(0.32, 0.42), rng.uniform(0.15, 0.28)
    u = np.array([math.cos(phi), math.sin(phi), 0.0])
    v = np.array([-u[1], u[0], 0.0])
    c = distance * u
    t = 0.02
    lift = up(h / 2 - 0.01)
    boxes = [
        FLOOR,
        box(c + (sx / 2 + t / 2) * u + lift, (t, sy + 2 * t, h), phi, "wall far"),
        box(c - (sx / 2 + t / 2) * u + lift, (t, sy + 2 * t, h), phi, "wall near"),
        box(c + (sy / 2 + t / 2) * v + lift, (sx, t, h), phi, "wall left"),
        box(c - (sy / 2 + t / 2) * v + lift, (sx, t, h), phi, "wall right"),
    ]
    scene = planning.Scene(boxes=boxes)
    beside = phi + rng.choice([-1, 1]) * rng.uniform(0.8, 1.4)
    start_at = polar(rng.uniform(0.4, 0.6), beside, rng.uniform(0.08, 0.2))

    def into(r: np.random.Generator) -> np.ndarray:
        at = c + r.uniform(-0.2, 0.2) * sx * u + r.uniform(-0.2, 0.2) * sy * v
        return pose(at + up(r.uniform(0.06, 0.14) + 0.3 * h), DOWN, any_spin(r))

    found = ends(rng, scene, lambda r: pose(start_at, DOWN, any_spin(r)), into, beside)
    return None if found is None else (scene, *found)


def cage(rng: np.random.Generator) -> Draw:
    n = int(rng.integers(7, 10))
    radius = rng.uniform(0.45, 0.55)
    offset = rng.uniform(0, 2 * np.pi)
    angles = offset + 2 * np.pi * np.arange(n) / n + rng.uniform(-0.05, 0.05, n)
    rings = (rng.uniform(0.2, 0.3), rng.uniform(0.65, 0.75))
    bar = rng.uniform(0.012, 0.025)
    height = 1.1
    cylinders = [
        planning.Cylinder(polar(radius, a, height / 2 - 0.01), [0, 0, 1], bar, height, f"bar {k}")
        for k, a in enumerate(angles)
    ]
    for z in rings:
        for k in range(n):
            p, q = polar(radius, angles[k], z), polar(radius, angles[(k + 1) % n], z)
            cylinders.append(
                planning.Cylinder(
                    (p + q) / 2, q - p, bar, float(np.linalg.norm(q - p)), f"ring {z:.2f} {k}"
                )
            )
    scene = planning.Scene(boxes=[FLOOR], cylinders=cylinders)
    a = int(rng.integers(n))
    b = (a + int(rng.integers(2, n - 1))) % n

    def middle(k: int) -> float:
        return float(angles[k] + wrap(np.array(angles[(k + 1) % n] - angles[k])) / 2)

    def window(k: int) -> PoseSampler:
        phi = middle(k)
        out = np.array([math.cos(phi), math.sin(phi), 0.0])

        def sample(r: np.random.Generator) -> np.ndarray:
            z = rings[0] + r.uniform(0.3, 0.7) * (rings[1] - rings[0])
            at = polar(radius + r.uniform(0.03, 0.15), phi, z)
            return pose(at, tilted(out, r.uniform(0.2, 1.2)), any_spin(r))

        return sample

    found = ends(rng, scene, window(a), window(b), middle(a))
    return None if found is None else (scene, *found)


GENERATORS: dict[str, Callable[[np.random.Generator], Draw]] = {
    "empty": empty,
    "table": table,
    "shelf": shelf,
    "box": open_box,
    "cage": cage,
}


def draw(family: str, k: int, seed: int = 0) -> Problem | None:
    """Draw ``k`` of a family: the problem, or None when it is rejected."""
    rng = np.random.default_rng([seed, FAMILIES.index(family), k])
    made = GENERATORS[family](rng)
    if made is None:
        return None
    scene, start, goal = made
    if not np.all(planning.is_free(MODEL, scene, np.array([start, goal]))):
        return None
    if family != "empty" and planning.edges_free(MODEL, scene, start, goal):
        return None  # trivial: the straight edge is free
    return Problem(family, k, scene, np.asarray(start, float), np.asarray(goal, float))


def problems(family: str, count: int, seed: int = 0, max_draws: int = 1000) -> list[Problem]:
    """The first ``count`` kept draws of a family."""
    kept: list[Problem] = []
    for k in range(max_draws):
        if len(kept) == count:
            break
        problem = draw(family, k, seed)
        if problem is not None:
            kept.append(problem)
    return kept
