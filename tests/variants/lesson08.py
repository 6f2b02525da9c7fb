"""Lesson 08: other correct ways to write the exercises, and known mistakes."""

from tests.variants import Variant

# ------------------------------------------------------------------------- 8.1 sample_polyline

_POLYLINE = """
def sample_polyline(corners, step=1e-3, closed=False):
    corners = np.asarray(corners, dtype=float)
    ends = np.roll(corners, -1, axis=0) if closed else corners[1:]
    starts = corners[: len(ends)]
    lengths = np.linalg.norm(ends - starts, axis=1)
    pieces = {pieces}
    parts = []
    for a, b, n in zip(starts, ends, pieces):
        {segment}
    samples = np.concatenate(parts) if parts else np.empty((0, 3))
    {finish}
"""

_SEGMENT = "parts.append(a + (np.arange(n) / n)[:, None] * (b - a))"
_FINISH = "return samples if closed else np.vstack([samples, corners[-1:]])"


def _polyline(pieces="np.ceil(lengths / step).astype(int)", segment=_SEGMENT, finish=_FINISH):
    return _POLYLINE.format(pieces=pieces, segment=segment, finish=finish)


_URKIN_MARGIN = """
def sample_polyline(corners, step=1e-3, closed=False):
    corners = np.asarray(corners, dtype=float)
    if closed:
        corners = np.vstack([corners, corners[:1]])
    samples = []
    for a, b in zip(corners[:-1], corners[1:]):
        length = np.linalg.norm(b - a)
        if length == 0.0:
            continue
        n = int(np.floor(length / (step * (1 - 1e-9)))) + 1  # urkin's margin
        samples.extend(np.linspace(a, b, n, endpoint=False))
    if not closed:
        samples.append(corners[-1])
    return np.array(samples)
"""

_PURE_PYTHON = """
import math


def sample_polyline(corners, step=1e-3, closed=False):
    corners = [list(map(float, c)) for c in corners]
    pairs = list(zip(corners[:-1], corners[1:]))
    if closed:
        pairs.append((corners[-1], corners[0]))
    out = []
    for a, b in pairs:
        n = math.ceil(math.dist(a, b) / step)
        for i in range(n):
            out.append([a[j] + i / n * (b[j] - a[j]) for j in range(3)])
    if not closed:
        out.append(corners[-1])
    return np.array(out)
"""

_SEED000 = """
def sample_polyline(corners, step=1e-3, closed=False):
    corners = np.asarray(corners, dtype=float)
    if closed:
        corners = np.vstack([corners, corners[:1]])
    return np.concatenate([np.linspace(a, b, 20) for a, b in zip(corners[:-1], corners[1:])])
"""

# ------------------------------------------------------------------------ 8.3 quintic_scaling

_QUINTIC = """
def quintic_scaling(t, T):
    tau = {tau}
    s = {s}
    s_dot = {s_dot}
    s_ddot = {s_ddot}
    return s, s_dot, s_ddot
"""


def _quintic(
    tau="np.clip(np.asarray(t, dtype=float) / T, 0.0, 1.0)",
    s="10 * tau**3 - 15 * tau**4 + 6 * tau**5",
    s_dot="(30 * tau**2 - 60 * tau**3 + 30 * tau**4) / T",
    s_ddot="(60 * tau - 180 * tau**2 + 120 * tau**3) / T**2",
):
    return _QUINTIC.format(tau=tau, s=s, s_dot=s_dot, s_ddot=s_ddot)


_QUINTIC_WHERE = """
def quintic_scaling(t, T):
    t = np.asarray(t, dtype=float)
    tau = t / T
    inside = (t >= 0) & (t <= T)
    s = np.where(t < 0, 0.0, np.where(t > T, 1.0, np.polyval([6, -15, 10, 0, 0, 0], tau)))
    s_dot = np.where(inside, np.polyval([30, -60, 30, 0, 0], tau) / T, 0.0)
    s_ddot = np.where(inside, np.polyval([120, -180, 60, 0], tau) / T**2, 0.0)
    return s, s_dot, s_ddot
"""

_QUINTIC_FLOAT32 = """
def quintic_scaling(t, T):
    tau = np.clip(np.asarray(t, dtype=np.float32) / np.float32(T), 0, 1).astype(np.float32)
    T = np.float32(T)
    s = tau**3 * (10 - 15 * tau + 6 * tau**2)
    return s, 30 * tau**2 * (1 - tau) ** 2 / T, 60 * tau * (1 - tau) * (1 - 2 * tau) / T**2
"""

# ----------------------------------------------------------------------- 8.4 minimum_duration

_DURATION = """
def minimum_duration(distance, max_velocity, max_acceleration):
    d = {d}
    v = np.asarray(max_velocity, dtype=float)
    a = np.asarray(max_acceleration, dtype=float)
    {refuse}
    by_velocity = {velocity}
    by_acceleration = {acceleration}
    return {result}
"""

_REFUSE = (
    "if np.any(v <= 0) or np.any(a <= 0):\n"
    "        raise ValueError('max_velocity and max_acceleration must be > 0')"
)


def _duration(
    d="np.abs(np.asarray(distance, dtype=float))",
    refuse=_REFUSE,
    velocity="15 * d / (8 * v)",
    acceleration="np.sqrt(10 * d / (np.sqrt(3) * a))",
    result="float(np.max(np.maximum(by_velocity, by_acceleration)))",
):
    return _DURATION.format(
        d=d, refuse=refuse, velocity=velocity, acceleration=acceleration, result=result
    )


_DURATION_URKIN = """
def minimum_duration(distance, max_velocity, max_acceleration):
    d = np.abs(np.asarray(distance, dtype=float))
    v = np.asarray(max_velocity, dtype=float)
    a = np.asarray(max_acceleration, dtype=float)
    if not (np.all(v > 0) and np.all(a > 0)):
        raise ValueError("limits must be > 0")
    moving = d > 0
    if not moving.any():
        return 0.0
    V = np.min(v[moving] / d[moving])  # the largest s-dot every joint allows
    A = np.min(a[moving] / d[moving])
    return float(max(15 / (8 * V), np.sqrt(10 / (np.sqrt(3) * A))))
"""

_DURATION_LOOP = """
import math


def minimum_duration(distance, max_velocity, max_acceleration):
    T = 0.0
    for d, v, a in zip(distance, max_velocity, max_acceleration):
        if v <= 0 or a <= 0:
            raise ValueError(f"limits must be positive, got {v} and {a}")
        d = abs(d)
        T = max(T, 1.875 * d / v, math.sqrt(d * 10 / math.sqrt(3) / a))
    return T
"""

# -------------------------------------------------------------------------- 8.2 track_nearest

_TRACK = """
def track_nearest(robot, poses, q0, solve_all):
    previous = np.array(q0, dtype=float)
    q = {rows}
    ok = np.zeros(len(poses), dtype=bool)
    for k, T in enumerate(poses):
        solutions = np.asarray(solve_all(robot, T), dtype=float).reshape(-1, 6)
        if len(solutions) == 0:
            {failure}
            continue
        base = {base}
        gaps = {gaps}
        best = {best}
        previous = {continued}
        q[k], ok[k] = previous, True
    return q, ok
"""

_WRAP = "(solutions - base + np.pi) % (2 * np.pi) - np.pi"


def _track(
    rows="np.empty((len(poses), 6))",
    failure="q[k] = previous",
    base="previous",
    gaps=f"np.linalg.norm({_WRAP}, axis=1)",
    best="int(np.argmin(gaps))",
    continued="base + ((solutions[best] - base + np.pi) % (2 * np.pi) - np.pi)",
):
    return _TRACK.format(
        rows=rows, failure=failure, base=base, gaps=gaps, best=best, continued=continued
    )


_TRACK_WRAP_ANGLES = """
from urkin.transforms import wrap_angles


def track_nearest(robot, poses, q0, solve_all):
    q, ok = [], []
    current = np.asarray(q0, dtype=float)
    for T in poses:
        solutions = solve_all(robot, T)
        if len(solutions) > 0:
            differences = wrap_angles(np.asarray(solutions) - current)  # into (-pi, pi]
            current = current + differences[np.linalg.norm(differences, axis=1).argmin()]
        q.append(current.copy())
        ok.append(len(solutions) > 0)
    return np.array(q), np.array(ok)
"""

_TRACK_ROUND = """
def track_nearest(robot, poses, q0, solve_all):
    turn = 2 * np.pi
    previous = np.asarray(q0, dtype=float)
    rows, found = [], []
    for T in poses:
        sols = np.asarray(solve_all(robot, T)).reshape(-1, 6)
        found.append(len(sols) > 0)
        if found[-1]:
            # each solution turned by whole turns to its equivalent nearest previous
            shifted = sols + turn * np.round((previous - sols) / turn)
            previous = shifted[np.argmin(np.sum((shifted - previous) ** 2, axis=1))]
        rows.append(previous)
    return np.vstack(rows), np.array(found, dtype=bool)
"""

# ------------------------------------------------------------------------ 8.5 read_trajectory

_READ = """
def read_trajectory(robot, q):
    q = np.asarray(q, dtype=float)
    shoulder = {shoulder}
    factors = np.column_stack([shoulder, {elbow}, {wrist}])
    signs = np.sign(factors)
    changed = signs[1:] * signs[:-1] < 0
    names = ("shoulder", "elbow", "wrist")
    flips = {{n: (np.flatnonzero(changed[:, i]) + {shift}).tolist() for i, n in enumerate(names)}}
    outside = {outside}
    return {{"flips": flips, "wound": {wound}}}
"""

_SHOULDER = (
    "robot.a2 * np.cos(q[:, 1]) + robot.a3 * np.cos(q[:, 1] + q[:, 2])"
    " + robot.d5 * np.sin(q[:, 1] + q[:, 2] + q[:, 3])"
)


def _read(
    shoulder=_SHOULDER,
    elbow="np.sin(q[:, 2])",
    wrist="np.sin(q[:, 4])",
    shift=0,
    outside="(np.abs(q) > 2 * np.pi).any(axis=0)",
    wound="(np.flatnonzero(outside) + 1).tolist()",
):
    return _READ.format(
        shoulder=shoulder,
        elbow=elbow,
        wrist=wrist,
        shift=shift,
        outside=outside,
        wound=wound,
    )


_READ_LOOPS = """
import math


def read_trajectory(robot, q):
    def factors(row):
        q2, q3, q4, q5 = row[1], row[2], row[3], row[4]
        return (
            robot.a2 * math.cos(q2)
            + robot.a3 * math.cos(q2 + q3)
            + robot.d5 * math.sin(q2 + q3 + q4),
            math.sin(q3),
            math.sin(q5),
        )

    rows = [factors(row) for row in q]
    flips = {"shoulder": [], "elbow": [], "wrist": []}
    for k in range(len(rows) - 1):
        for i, name in enumerate(flips):
            if rows[k][i] * rows[k + 1][i] < 0:
                flips[name].append(k)
    wound = [j + 1 for j in range(6) if min(r[j] for r in q) < -2 * math.pi
             or max(r[j] for r in q) > 2 * math.pi]
    return {"flips": flips, "wound": wound}
"""

_READ_DIFF = """
def read_trajectory(robot, q):
    q = np.asarray(q)
    s234 = np.sin(q[:, 1:4].sum(axis=1))
    shoulder = robot.a2 * np.cos(q[:, 1]) + robot.a3 * np.cos(q[:, 1] + q[:, 2]) + robot.d5 * s234
    positive = np.column_stack([shoulder, np.sin(q[:, 2]), np.sin(q[:, 4])]) > 0
    changed = np.diff(positive.astype(int), axis=0) != 0
    flips = dict(zip(["shoulder", "elbow", "wrist"], (np.nonzero(c)[0] for c in changed.T)))
    wound = np.nonzero((q.min(axis=0) < -2 * np.pi) | (q.max(axis=0) > 2 * np.pi))[0] + 1
    return {"flips": flips, "wound": wound}
"""

CORRECT = [
    Variant("8.1", "a loop over segments", _polyline()),
    Variant("8.1", "urkin's margin, linspace without the end", _URKIN_MARGIN),
    Variant("8.1", "pure Python lists", _PURE_PYTHON),
    Variant("8.3", "np.where and np.polyval", _QUINTIC_WHERE),
    Variant("8.3", "float32", _QUINTIC_FLOAT32),
    Variant(
        "8.3",
        "Horner and factored derivatives",
        _quintic(
            s="tau**3 * (10 + tau * (-15 + 6 * tau))",
            s_dot="30 * (tau * (1 - tau)) ** 2 / T",
            s_ddot="60 * tau * (1 - tau) * (1 - 2 * tau) / (T * T)",
        ),
    ),
    Variant("8.4", "the largest allowed s-dot and s-ddot", _DURATION_URKIN),
    Variant("8.4", "a loop over joints", _DURATION_LOOP),
    Variant("8.2", "urkin.transforms.wrap_angles, lists", _TRACK_WRAP_ANGLES),
    Variant("8.2", "solutions shifted by whole turns", _TRACK_ROUND),
    Variant("8.2", "a template of the solution", _track()),
    Variant("8.5", "loops over samples", _READ_LOOPS),
    Variant("8.5", "np.diff of booleans, arrays", _READ_DIFF),
    Variant("8.5", "a template of the solution", _read()),
]

WRONG = [
    # ------------------------------------------------------------------------------ 8.1
    Variant("8.1", "seed 000's 20 per side", _SEED000, points=0, mistake="same number of samples"),
    Variant(
        "8.1",
        "linspace with both ends",
        _polyline(segment="parts.append(np.linspace(a, b, n + 1))"),
        points=0,
        mistake="corners repeated",
    ),
    Variant(
        "8.1",
        "round instead of ceil",
        _polyline(pieces="np.round(lengths / step).astype(int)"),
        points=1,
        mistake="round(L / step)",
    ),
    Variant(
        "8.1",
        "int instead of ceil",
        _polyline(pieces="(lengths / step).astype(int)"),
        points=0,
        mistake="int(L / step)",
    ),
    Variant(
        "8.1",
        "end point missing",
        _polyline(finish="return samples"),
        points=1,
        mistake="end point is missing",
    ),
    Variant(
        "8.1",
        "closed repeats its start",
        _polyline(
            finish="return np.vstack([samples, corners[:1]]) if closed else np.vstack("
            "[samples, corners[-1:]])"
        ),
        points=2,
        mistake="repeats its start",
    ),
    Variant(
        "8.1",
        "closed ignored",
        _polyline()
        .replace("if closed else corners[1:]", "if False else corners[1:]")
        .replace("return samples if closed else", "return"),
        points=2,
        mistake="closed=True ignored",
    ),
    Variant(
        "8.1",
        "a zero-length segment adds a sample",
        _polyline(pieces="np.maximum(np.ceil(lengths / step), 1).astype(int)"),
        points=3,
        mistake="zero-length segment",
    ),
    # ------------------------------------------------------------------------------ 8.3
    Variant(
        "8.3",
        "cubic",
        _quintic(
            s="3 * tau**2 - 2 * tau**3",
            s_dot="6 * tau * (1 - tau) / T",
            s_ddot="np.where((t >= 0) & (t <= T), (6 - 12 * tau) / T**2, 0.0)",
        ),
        points=0,
        mistake="cubic",
    ),
    Variant(
        "8.3",
        "derivatives in tau",
        _quintic(
            s_dot="30 * tau**2 - 60 * tau**3 + 30 * tau**4",
            s_ddot="60 * tau - 180 * tau**2 + 120 * tau**3",
        ),
        points=0,
        mistake="with respect to τ",
    ),
    Variant(
        "8.3",
        "s-ddot over T once",
        _quintic(s_ddot="(60 * tau - 180 * tau**2 + 120 * tau**3) / T"),
        points=0,
        mistake="divided by T only once",
    ),
    Variant(
        "8.3",
        "not clipped",
        _quintic(tau="np.asarray(t, dtype=float) / T"),
        points=2,
        mistake="not clipped",
    ),
    # ------------------------------------------------------------------------------ 8.4
    Variant(
        "8.4",
        "one T per joint",
        _duration(result="np.maximum(by_velocity, by_acceleration)"),
        points=0,
        mistake="one T per joint",
    ),
    Variant(
        "8.4",
        "sum over joints",
        _duration(result="float(np.sum(np.maximum(by_velocity, by_acceleration)))"),
        points=0,
        mistake="joints' durations added",
    ),
    Variant(
        "8.4",
        "velocity and acceleration times added",
        _duration(result="float(by_velocity.max() + by_acceleration.max())"),
        points=0,
        mistake="velocity-limited and acceleration-limited durations added",
    ),
    Variant(
        "8.4",
        "cubic's peaks",
        _duration(velocity="1.5 * d / v", acceleration="np.sqrt(6 * d / a)"),
        points=0,
        mistake="cubic's peaks",
    ),
    Variant(
        "8.4",
        "velocity only",
        _duration(result="float(np.max(by_velocity))"),
        points=0,
        mistake="only the velocity limit",
    ),
    Variant(
        "8.4",
        "acceleration only",
        _duration(result="float(np.max(by_acceleration))"),
        points=0,
        mistake="only the acceleration limit",
    ),
    Variant(
        "8.4",
        "signed distances, NaN",
        _duration(d="np.asarray(distance, dtype=float)"),
        points=0,
        mistake="signed distances",
    ),
    Variant(
        "8.4",
        "signed distances, nanmax",
        _duration(
            d="np.asarray(distance, dtype=float)",
            result="float(np.nanmax(np.maximum(by_velocity, by_acceleration)))",
        ),
        points=0,
        mistake="signed distances",
    ),
    Variant(
        "8.4",
        "no ValueError",
        _duration(refuse="pass"),
        points=2,
        mistake="no ValueError",
    ),
    # ------------------------------------------------------------------------------ 8.2
    Variant(
        "8.2",
        "seed 000's overwrite: a failed row left at zero",
        _track(rows="np.zeros((len(poses), 6))", failure="pass"),
        points=3,
        mistake="left unset",
    ),
    Variant(
        "8.2",
        "a failed row left unset (NaN)",
        _track(rows="np.full((len(poses), 6), np.nan)", failure="pass"),
        points=3,
        mistake="left unset",
    ),
    Variant(
        "8.2",
        "a failed row set to q0",
        _track(failure="q[k] = q0"),
        points=3,
        mistake="row is q0",
    ),
    Variant(
        "8.2",
        "ok not recorded",
        _track(failure="q[k], ok[k] = previous, True"),
        points=3,
        mistake="ok not recorded",
    ),
    Variant("8.2", "the first solution", _track(best="0"), points=0, mistake="first solution"),
    Variant(
        "8.2",
        "nearest by plain differences",
        _track(gaps="np.linalg.norm(solutions - base, axis=1)"),
        points=2,
        mistake="without wrapping the difference",
    ),
    Variant(
        "8.2",
        "solutions returned as they are",
        _track(continued="solutions[best]"),
        points=2,
        mistake="no shortest-turn continuation",
    ),
    Variant(
        "8.2",
        "every pose compared with q0",
        _track(base="np.asarray(q0, dtype=float)"),
        points=3,
        mistake="compared with (and continued from) q0",
    ),
    # ------------------------------------------------------------------------------ 8.5
    Variant(
        "8.5",
        "sign of q3 and q5",
        _read(elbow="q[:, 2]", wrist="q[:, 4]"),
        points=1,
        mistake="sign of q3",
    ),
    Variant("8.5", "flips at k + 1", _read(shift=1), points=1, mistake="off by one"),
    Variant(
        "8.5",
        "shoulder without d5",
        _read(shoulder="robot.a2 * np.cos(q[:, 1]) + robot.a3 * np.cos(q[:, 1] + q[:, 2])"),
        points=1,
        mistake="without d5",
    ),
    Variant(
        "8.5",
        "net turns",
        _read(outside="np.abs(q[-1] - q[0]) >= 2 * np.pi"),
        points=2,
        mistake="net turns",
    ),
    Variant(
        "8.5",
        "0-based joints",
        _read(wound="np.flatnonzero(outside).tolist()"),
        points=2,
        mistake="0-based",
    ),
    Variant(
        "8.5",
        "leaving [-pi, pi]",
        _read(outside="(np.abs(q) > np.pi).any(axis=0)"),
        points=2,
        mistake="leaving [−π, π]",
    ),
    Variant(
        "8.5",
        "last sample only",
        _read(outside="np.abs(q[-1]) > 2 * np.pi"),
        points=2,
        mistake="only the last sample",
    ),
]
