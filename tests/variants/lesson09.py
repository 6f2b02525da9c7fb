"""Lesson 09: other correct ways to write the exercises, and known mistakes."""

from tests.variants import Variant

# --------------------------------------------------------------------- 9.1 sphere_box_distance

_BOX = """
def sphere_box_distance(centre, radius, box_centre, box_size, box_R):
    R = np.asarray(box_R, dtype=float)
    offset = np.asarray(centre, dtype=float) - np.asarray(box_centre, dtype=float)
    p = {local}
    h = {half}
    q = np.abs(p) - h
    outside = {outside}
    inside = {inside}
    return float(outside + inside {radius})
"""


def _box(
    local="R.T @ offset",
    half="np.asarray(box_size, dtype=float) / 2",
    outside="np.linalg.norm(np.maximum(q, 0.0))",
    inside="min(q.max(), 0.0)",
    radius="- radius",
):
    return _BOX.format(local=local, half=half, outside=outside, inside=inside, radius=radius)


_BOX_CLIPPED_POINT = """
def sphere_box_distance(centre, radius, box_centre, box_size, box_R):
    R = np.array(box_R, dtype=float)
    local = (np.array(centre, dtype=float) - box_centre) @ R  # coordinates along the box's axes
    half = 0.5 * np.array(box_size, dtype=float)
    closest = np.clip(local, -half, half)
    if np.all(closest == local):  # inside: the nearest face
        return -np.min(half - np.abs(local)) - radius
    return np.linalg.norm(local - closest) - radius
"""

_BOX_LOOPS = """
import math


def sphere_box_distance(centre, radius, box_centre, box_size, box_R):
    local = [
        sum(box_R[i][k] * (centre[i] - box_centre[i]) for i in range(3)) for k in range(3)
    ]
    gaps = [abs(local[k]) - box_size[k] / 2 for k in range(3)]
    if max(gaps) > 0:
        return math.sqrt(sum(max(g, 0.0) ** 2 for g in gaps)) - radius
    return max(gaps) - radius
"""

_BOX_FLOAT32 = """
def sphere_box_distance(centre, radius, box_centre, box_size, box_R):
    R = np.asarray(box_R, dtype=np.float32)
    p = R.T @ (np.asarray(centre, dtype=np.float32) - np.asarray(box_centre, dtype=np.float32))
    q = np.abs(p) - np.asarray(box_size, dtype=np.float32) / 2
    return np.float32(np.linalg.norm(np.maximum(q, 0)) + min(q.max(), 0) - radius)
"""

# ------------------------------------------------------------------------ 9.2 samples_needed

_SAMPLES = """
def samples_needed(qa, qb, rho, resolution):
    dq = np.asarray(qb, dtype=float) - np.asarray(qa, dtype=float)
    rho = np.asarray(rho, dtype=float)
    bound = {bound}
    pieces = {pieces}
    return {result}
"""


def _samples(
    bound="np.sum(np.abs(dq) * rho)",
    pieces="max(1, math.ceil(bound / resolution))",
    result="pieces + 1",
):
    return _SAMPLES.format(bound=bound, pieces=pieces, result=result)


_SAMPLES_PURE = """
def samples_needed(qa, qb, rho, resolution):
    bound = sum(abs(b - a) * r for a, b, r in zip(qa, qb, rho))
    pieces = -(-bound // resolution)  # ceiling division
    return int(max(pieces, 1)) + 1
"""

_SAMPLES_DOT = """
def samples_needed(qa, qb, rho, resolution):
    travel = np.abs(np.subtract(qb, qa)) @ np.asarray(rho)
    return int(np.ceil(travel / resolution).clip(min=1)) + 1
"""

# -------------------------------------------------------------------------- 9.3 path_is_free

_PATH = """
def path_is_free(is_free, path, rho, resolution):
    path = np.asarray(path, dtype=float)
    {waypoints}
    for qa, qb in zip(path[:-1], path[1:]):
        t = {t}
        if not np.all(is_free(qa + t[:, None] * (qb - qa))):
            return False
    return True
"""


def _path(
    waypoints="pass",
    t="np.linspace(0.0, 1.0, samples_needed(qa, qb, rho, resolution))",
):
    return _PATH.format(waypoints=waypoints, t=t)


_PATH_ONE_CALL = """
def path_is_free(is_free, path, rho, resolution):
    path = np.asarray(path, dtype=float)
    chunks = [path[:1]]
    for qa, qb in zip(path[:-1], path[1:]):
        n = samples_needed(qa, qb, rho, resolution)
        chunks.append(qa + np.linspace(0, 1, n)[1:, None] * (qb - qa))  # the start is the last end
    return bool(is_free(np.concatenate(chunks)).all())
"""

_PATH_ONE_AT_A_TIME = """
def path_is_free(is_free, path, rho, resolution):
    for k in range(len(path) - 1):
        qa, qb = np.asarray(path[k], dtype=float), np.asarray(path[k + 1], dtype=float)
        n = samples_needed(qa, qb, rho, resolution)
        for i in range(n):
            if not is_free(qa + (i / (n - 1)) * (qb - qa)):
                return False
    return True
"""

_PATH_WAYPOINTS_ONLY = """
def path_is_free(is_free, path, rho, resolution):
    return bool(np.all(is_free(np.asarray(path, dtype=float))))
"""

_PATH_TOO_MANY = """
def path_is_free(is_free, path, rho, resolution):
    path = np.asarray(path, dtype=float)
    t = np.linspace(0.0, 1.0, 2000)[:, None]
    return all(np.all(is_free(qa + t * (qb - qa))) for qa, qb in zip(path[:-1], path[1:]))
"""

# ---------------------------------------------------------------------------------- 9.4 steer

_STEER = """
def steer(q_near, q_rand, step):
    q_near = np.asarray(q_near, dtype=float)
    q_rand = np.asarray(q_rand, dtype=float)
    delta = q_rand - q_near
    size = {size}
    {near}
    return {result}
"""


def _steer(
    size="np.max(np.abs(delta))",
    near="if size <= step:\n        return q_rand.copy()",
    result="q_near + delta * (step / size)",
):
    return _STEER.format(size=size, near=near, result=result)


_STEER_MIN = """
def steer(q_near, q_rand, step):
    q_near, q_rand = np.asarray(q_near, dtype=float), np.asarray(q_rand, dtype=float)
    delta = q_rand - q_near
    largest = np.abs(delta).max()
    return q_near + delta * min(1.0, step / largest) if largest > 0 else q_near.copy()
"""

_STEER_LISTS = """
def steer(q_near, q_rand, step):
    delta = [b - a for a, b in zip(q_near, q_rand)]
    largest = max(abs(d) for d in delta)
    if largest <= step:
        return list(q_rand)
    return [a + d * step / largest for a, d in zip(q_near, delta)]
"""

CORRECT = [
    Variant("9.1", "the clipped closest point", _BOX_CLIPPED_POINT),
    Variant("9.1", "pure Python loops", _BOX_LOOPS),
    Variant("9.1", "float32", _BOX_FLOAT32),
    Variant("9.2", "pure Python, ceiling division", _SAMPLES_PURE),
    Variant("9.2", "a dot product, np.ceil", _SAMPLES_DOT),
    Variant(
        "9.2",
        "a NumPy integer",
        _samples(pieces="max(1, np.ceil(bound / resolution).astype(np.int64))"),
    ),
    Variant("9.2", "a NumPy int32", _samples(result="np.int32(pieces + 1)")),
    Variant("9.3", "one call of is_free for the whole path", _PATH_ONE_CALL),
    Variant("9.3", "one configuration at a time", _PATH_ONE_AT_A_TIME),
    Variant("9.3", "a template of the solution", _path()),
    Variant("9.4", "min(1, step / largest)", _STEER_MIN),
    Variant("9.4", "lists", _STEER_LISTS),
    Variant("9.4", "a template of the solution", _steer()),
]

WRONG = [
    # ------------------------------------------------------------------------------ 9.1
    Variant("9.1", "rotation ignored", _box(local="offset"), points=0, mistake="rotation ignored"),
    Variant(
        "9.1",
        "rotation the wrong way round",
        _box(local="R @ offset"),
        points=0,
        mistake="the wrong way round",
    ),
    Variant(
        "9.1",
        "full sizes as half sizes",
        _box(half="np.asarray(box_size, dtype=float)"),
        points=0,
        mistake="used as half sizes",
    ),
    Variant(
        "9.1",
        "inside clipped to zero",
        _box(inside="0.0"),
        points=2,
        mistake="clipped to 0",
    ),
    Variant(
        "9.1",
        "inside positive",
        _box(inside="abs(min(q.max(), 0.0))"),
        points=2,
        mistake="came out positive",
    ),
    Variant("9.1", "radius not subtracted", _box(radius=""), points=0, mistake="not subtracted"),
    Variant("9.1", "radius added", _box(radius="+ radius"), points=0, mistake="radius added"),
    Variant(
        "9.1",
        "largest gap outside",
        _box(outside="np.max(np.maximum(q, 0.0))"),
        points=1,
        mistake="largest per-axis gap",
    ),
    Variant(
        "9.1",
        "gaps added",
        _box(outside="np.sum(np.maximum(q, 0.0))"),
        points=1,
        mistake="per-axis gaps added",
    ),
    # ------------------------------------------------------------------------------ 9.2
    Variant(
        "9.2",
        "max norm",
        _samples(bound="np.max(np.abs(dq) * rho)"),
        points=0,
        mistake="largest joint term",
    ),
    Variant(
        "9.2",
        "Euclidean norm",
        _samples(bound="np.linalg.norm(dq * rho)"),
        points=0,
        mistake="Euclidean norm",
    ),
    Variant(
        "9.2",
        "the largest rho for every joint",
        _samples(bound="rho.max() * np.sum(np.abs(dq))"),
        points=0,
        mistake="one lever arm",
    ),
    Variant(
        "9.2",
        "radians as metres",
        _samples(bound="np.sum(np.abs(dq))"),
        points=0,
        mistake="without their lever arms",
    ),
    Variant(
        "9.2",
        "signed changes",
        _samples(bound="np.sum(dq * rho)"),
        points=0,
        mistake="signed joint changes",
    ),
    Variant(
        "9.2",
        "pieces, not samples",
        _samples(result="pieces"),
        points=0,
        mistake="one sample short",
    ),
    Variant(
        "9.2",
        "floor",
        _samples(pieces="max(1, math.floor(bound / resolution))"),
        points=0,
        mistake="one sample short",
    ),
    Variant(
        "9.2",
        "round",
        _samples(pieces="round(bound / resolution)"),
        points=None,
        mistake="one sample short",
    ),
    Variant(
        "9.2",
        "a float count: max(1.0, np.ceil(D / res)) + 1",
        _samples(pieces="max(1.0, np.ceil(bound / resolution))"),
        points=0,
        mistake="returns a float; the count must be an int",
    ),
    Variant(
        "9.2",
        "a Python float count",
        _samples(result="float(pieces + 1)"),
        points=0,
        mistake="returns a float; the count must be an int",
    ),
    Variant(
        "9.2",
        "joint changes wrapped the short way",
        _samples(bound="np.sum(np.abs((dq + np.pi) % (2 * np.pi) - np.pi) * rho)"),
        points=2,
        mistake="Δq wrapped",
    ),
    # ------------------------------------------------------------------------------ 9.3
    Variant(
        "9.3",
        "waypoints only (MIT's autograder)",
        _PATH_WAYPOINTS_ONLY,
        points=0,  # the waypoint check is gated on a check of the edges
        mistake="only the waypoints",
    ),
    Variant(
        "9.3",
        "ten samples per edge",
        _path(t="np.linspace(0.0, 1.0, 10)"),
        points=None,  # 0 where an edge needs more than ten samples, as every free path's do
        mistake="fixed number of samples",
    ),
    Variant(
        "9.3",
        "the goal never checked",
        _path(
            t="np.arange(samples_needed(qa, qb, rho, resolution) - 1) / "
            "(samples_needed(qa, qb, rho, resolution) - 1)"
        ),
        points=3,
        mistake="last waypoint never checked",
    ),
    Variant(
        "9.3",
        "the start never checked",
        _path(
            t="np.arange(1, samples_needed(qa, qb, rho, resolution)) / "
            "(samples_needed(qa, qb, rho, resolution) - 1)"
        ),
        points=3,
        mistake="first waypoint never checked",
    ),
    Variant("9.3", "2000 samples per edge", _PATH_TOO_MANY, points=3, mistake="far more samples"),
    Variant(
        "9.3",
        "one sample short per edge",
        _path(t="np.linspace(0.0, 1.0, samples_needed(qa, qb, rho, resolution) - 1)"),
        points=3,
        mistake="sampled more coarsely",
    ),
    Variant(
        "9.3",
        "a quarter of the samples",
        _path(t="np.linspace(0.0, 1.0, max(2, samples_needed(qa, qb, rho, resolution) // 4))"),
        points=None,
        mistake="sampled more coarsely",
    ),
    # ------------------------------------------------------------------------------ 9.4
    Variant(
        "9.4",
        "overshoot",
        _steer(near="pass"),
        points=2,
        mistake="a full step even when",
    ),
    Variant("9.4", "no step limit", _steer(result="q_rand"), points=1, mistake="no step limit"),
    Variant(
        "9.4",
        "away from q_rand",
        _steer(result="q_near - delta * (step / size)"),
        points=1,
        mistake="goes away",
    ),
    Variant(
        "9.4",
        "from q_rand back",
        _steer(result="q_rand - delta * (step / size)"),
        points=1,
        mistake="back towards q_near",
    ),
    Variant(
        "9.4",
        "Euclidean step",
        _steer(size="np.linalg.norm(delta)"),
        points=0,
        mistake="Euclidean norm",
    ),
    Variant(
        "9.4",
        "each joint clipped",
        _steer(result="q_near + np.clip(delta, -step, step)"),
        points=1,
        mistake="clipped to ±step",
    ),
    Variant(
        "9.4",
        "not normalised",
        _steer(result="q_near + step * delta"),
        points=1,
        mistake="without dividing",
    ),
]
