"""Lesson 02 (DH forward kinematics): other correct ways to write its functions, and mistakes."""

from tests.variants import Variant

_UR5_CLOSED_FORM = """
    d1, a2, a3, d4, d5, d6 = 0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823
    q1, q2, q3, q4, q5, _ = q
    c1, s1, c5, s5 = np.cos(q1), np.sin(q1), np.cos(q5), np.sin(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)
"""

_TO_MODIFIED = """
def to_modified(rows):
    d, a, alpha = np.asarray(rows, dtype=float).T
    table = np.column_stack([{d}, {a}, {alpha}])
    return table, {tool}
"""


def _to_modified(
    d="d",
    a="np.r_[0.0, a[:-1]]",
    alpha="np.r_[0.0, alpha[:-1]]",
    tool="make_transform(p=[a[-1], 0, 0]) @ make_transform(rot_x(alpha[-1]))",
):
    """A to_modified whose table columns and tool are the given expressions."""
    return _TO_MODIFIED.format(d=d, a=a, alpha=alpha, tool=tool)


_FORMULA_GAP = """
def formula_gap(formula, robot, n=1000, seed=0):
    q = {draw}
    p_formula = np.array([formula(robot, q_k) for q_k in q], dtype=float)
    difference = p_formula - urkin.fk(robot, q)[:, :3, 3]
    distances = {distances}
    return {answer}
"""


def _formula_gap(
    draw="np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))",
    distances="np.linalg.norm(difference, axis=1)",
    answer="distances.max(), q[np.argmax(distances)]",
):
    """A formula_gap whose draw, distances and answer are the given expressions."""
    return _FORMULA_GAP.format(draw=draw, distances=distances, answer=answer)


_DH_FLOAT32 = """
def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                     [0, sa, ca, d], [0, 0, 0, 1]], dtype=np.float32)
"""

_FK_LOOP = """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for i in range(6):
        T = T @ dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i])
    return T
"""

_FORMULA_GAP_OWN_FK = """
def formula_gap(formula, robot, n=1000, seed=0):
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))
    p_formula = np.array([formula(robot, q_k) for q_k in q], dtype=float)
    p_true = np.array([forward_kinematics(robot, q_k)[:3, 3] for q_k in q])
    distances = np.linalg.norm(p_formula - p_true, axis=1)
    return distances.max(), q[np.argmax(distances)]
"""

CORRECT = [
    Variant(
        "2.1",
        "four elementary transforms multiplied",
        """
def dh_transform(theta, d, a, alpha):
    def rz(t):
        c, s = np.cos(t), np.sin(t)
        return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])

    def rx(t):
        c, s = np.cos(t), np.sin(t)
        return np.array([[1.0, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])

    tz, tx = np.eye(4), np.eye(4)
    tz[2, 3], tx[0, 3] = d, a
    return rz(theta) @ tz @ tx @ rx(alpha)
""",
    ),
    Variant(
        "2.1",
        "math module and nested lists",
        """
import math

def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return [[ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1]]
""",
    ),
    Variant(
        "2.1",
        "float32",
        """
def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                     [0, sa, ca, d], [0, 0, 0, 1]], dtype=np.float32)
""",
    ),
    Variant(
        "2.2",
        "reduce over a list of link transforms",
        """
from functools import reduce

def forward_kinematics(robot, q):
    links = [dh_transform(t, d, a, al) for t, d, a, al in zip(q, robot.d, robot.a, robot.alpha)]
    return reduce(np.matmul, links, np.eye(4))
""",
    ),
    Variant(
        "2.2",
        "index loop over the DH table, input validated",
        """
def forward_kinematics(robot, q):
    q = np.asarray(q, dtype=float)
    if q.shape != (6,):
        raise ValueError("q must have six angles")
    table = robot.dh_table()
    T = np.eye(4)
    for i in range(6):
        d_i, a_i, alpha_i = table[i]
        T = T @ dh_transform(q[i], d_i, a_i, alpha_i)
    return T
""",
    ),
    Variant(
        "2.2",
        "np.dot, with the lengths read from robot.lengths",
        """
def forward_kinematics(robot, q):
    d1, a2, a3, d4, d5, d6 = robot.lengths
    rows = [(d1, 0, np.pi / 2), (0, a2, 0), (0, a3, 0), (d4, 0, np.pi / 2), (d5, 0, -np.pi / 2),
            (d6, 0, 0)]
    T = np.identity(4)
    for angle, (d, a, alpha) in zip(list(q), rows):
        T = np.dot(T, dh_transform(angle, d, a, alpha))
    return T
""",
    ),
    Variant(
        "2.3",
        "the closed form, with the UR5's lengths typed in",
        f"""
def ur5_position(q):
{_UR5_CLOSED_FORM}
    return np.array([
        c1 * reach + d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234 * s5),
        s1 * reach - d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234 * s5),
        d1 + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5,
    ])
""",
    ),
    Variant(
        "2.3",
        "SymPy's formula lambdified once, outside the function",
        """
ur5_p = sp.lambdify(Q, p_general.subs(dict(zip(LENGTHS, urkin.robot("UR5").lengths))), "numpy")

def ur5_position(q):
    return np.asarray(ur5_p(*q), dtype=float).reshape(3)
""",
    ),
    Variant(
        "2.3",
        "math module, a tuple of floats",
        """
import math

def ur5_position(q):
    d1, a2, a3, d4, d5, d6 = urkin.robot("UR5").lengths
    q1, q2, q3, q4, q5, q6 = [float(x) for x in q]
    c1, s1, c5, s5 = math.cos(q1), math.sin(q1), math.cos(q5), math.sin(q5)
    c234, s234 = math.cos(q2 + q3 + q4), math.sin(q2 + q3 + q4)
    r = a2 * math.cos(q2) + a3 * math.cos(q2 + q3)
    x = c1 * r + d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234 * s5)
    y = s1 * r - d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234 * s5)
    z = d1 + a2 * math.sin(q2) + a3 * math.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5
    return (x, y, z)
""",
    ),
    Variant(
        "2.4",
        "sp.rot_axis-free product with nsimplify, simplified once at the end",
        """
def symbolic_fk(rows):
    q = sp.symbols(" ".join(f"q{i + 1}" for i in range(len(rows))), real=True)
    if len(rows) == 1:
        q = (q,)
    T = sp.eye(4)
    for qi, (d, a, alpha) in zip(q, rows):
        k = sp.nsimplify(alpha / (np.pi / 2), tolerance=1e-12, rational=True)
        alpha = k * sp.pi / 2 if k.is_Integer else sp.Float(alpha)
        Rz = sp.Matrix([[sp.cos(qi), -sp.sin(qi), 0, 0], [sp.sin(qi), sp.cos(qi), 0, 0],
                        [0, 0, 1, d], [0, 0, 0, 1]])
        Rx = sp.Matrix([[1, 0, 0, a], [0, sp.cos(alpha), -sp.sin(alpha), 0],
                        [0, sp.sin(alpha), sp.cos(alpha), 0], [0, 0, 0, 1]])
        T = T * Rz * Rx
    return sp.simplify(T) if len(rows) < 4 else T
""",
    ),
    Variant(
        "2.5",
        "read off the closed form with the signs of a2, a3 taken as abs",
        """
def upright_flange(robot):
    up = robot.d1 + abs(robot.a2) + abs(robot.a3) + robot.d5
    return [0, -robot.d4 - robot.d6, up]
""",
    ),
    Variant(
        "2.6",
        "a loop over rows, lists returned, Rx(α_n) before Tx(a_n)",
        """
def to_modified(rows):
    previous_a, previous_alpha = 0.0, 0.0
    table = []
    for d_i, a_i, alpha_i in rows:
        table.append([d_i, previous_a, previous_alpha])
        previous_a, previous_alpha = a_i, alpha_i
    tool = make_transform(rot_x(previous_alpha)) @ make_transform(p=[previous_a, 0.0, 0.0])
    return table, tool.tolist()
""",
    ),
    Variant(
        "2.6",
        "np.roll with the first row zeroed, urkin's dh_transform for the tool",
        """
from urkin.kinematics import dh_transform as link_transform


def to_modified(rows):
    table = np.array(rows, dtype=float)
    table[:, 1:] = np.roll(table[:, 1:], 1, axis=0)
    table[0, 1:] = 0.0
    return table, link_transform(0.0, 0.0, rows[-1][1], rows[-1][2])
""",
    ),
    Variant(
        "2.6",
        "float32",
        """
def to_modified(rows):
    rows = np.asarray(rows, dtype=np.float32)
    table = rows.copy()
    table[1:, 1:], table[0, 1:] = rows[:-1, 1:], 0
    c, s = np.cos(rows[-1, 2]), np.sin(rows[-1, 2])
    tool = np.array([[1, 0, 0, rows[-1, 1]], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]],
                    dtype=np.float32)
    return table, tool
""",
    ),
    Variant(
        "2.7",
        "one configuration at a time, the student's forward_kinematics, a list back",
        """
import math


def formula_gap(formula, robot, n=1000, seed=0):
    rng = np.random.default_rng(seed)
    gap, q_worst = -1.0, None
    for _ in range(n):
        q = rng.uniform(-np.pi, np.pi, 6)
        p = forward_kinematics(robot, q)[:3, 3]
        distance = math.dist(formula(robot, q), p)
        if distance > gap:
            gap, q_worst = distance, q
    return [gap, list(q_worst)]
""",
    ),
    Variant(
        "2.7",
        "sum of squares, np.sqrt, an array answer",
        _formula_gap(
            distances="np.sqrt((difference**2).sum(axis=1))",
            answer="np.float64(distances.max()), q[distances == distances.max()][0]",
        ),
    ),
    # an answer built on a float32 dh_transform (full marks in 2.1) is as precise as float32
    Variant(
        "2.2",
        "float64 product of a float32 dh_transform",
        _FK_LOOP,
        also=(("dh_transform", _DH_FLOAT32),),
    ),
    Variant(
        "2.2",
        "float32 product of a float32 dh_transform",
        """
def forward_kinematics(robot, q):
    T = np.eye(4, dtype=np.float32)
    for i in range(6):
        T = T @ dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i])
    return T
""",
        also=(("dh_transform", _DH_FLOAT32),),
    ),
    Variant(
        "2.7",
        "the student's forward_kinematics on a float32 dh_transform",
        _FORMULA_GAP_OWN_FK,
        also=(("forward_kinematics", _FK_LOOP), ("dh_transform", _DH_FLOAT32)),
    ),
]

WRONG = [
    Variant(
        "2.1",
        "degrees",
        """
def dh_transform(theta, d, a, alpha):
    theta, alpha = np.radians(theta), np.radians(alpha)
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                     [0, sa, ca, d], [0, 0, 0, 1.0]])
""",
        points=1,
        mistake="θ and α treated as degrees",
    ),
    Variant(
        "2.1",
        "modified DH",
        """
def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st, 0, a], [st * ca, ct * ca, -sa, -sa * d],
                     [st * sa, ct * sa, ca, ca * d], [0, 0, 0, 1.0]])
""",
        points=1,
        mistake="modified (Craig) DH",
    ),
    Variant(
        "2.1",
        "rotation block transposed",
        """
def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    T = np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                  [0, sa, ca, d], [0, 0, 0, 1.0]])
    T[:3, :3] = T[:3, :3].T
    return T
""",
        points=1,
        mistake="rotation block is transposed",
    ),
    Variant(
        "2.1",
        "urkin's dh_transform imported under the exercise's name",
        "from urkin.kinematics import dh_transform\n",
        points=0,
    ),
    Variant(
        "2.2",
        "a2 and a3 with the wrong sign",
        """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for angle, d_i, a_i, alpha_i in zip(q, robot.d, -robot.a, robot.alpha):
        T = T @ dh_transform(angle, d_i, a_i, alpha_i)
    return T
""",
        points=1,
        mistake="a2 and a3 with the wrong sign",
    ),
    Variant(
        "2.2",
        "links multiplied in reverse order",
        """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for angle, d_i, a_i, alpha_i in zip(q, robot.d, robot.a, robot.alpha):
        T = dh_transform(angle, d_i, a_i, alpha_i) @ T
    return T
""",
        mistake="multiplied in reverse order",
    ),
    Variant(
        "2.2",
        "a list breaks it: q + 0.0 on an array only",
        """
def forward_kinematics(robot, q):
    q = q + 0.0
    T = np.eye(4)
    for i in range(6):
        T = T @ dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i])
    return T
""",
        points=4,
    ),
    Variant(
        "2.2",
        "joint index off by one (q[i - 1])",
        """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for i in range(6):
        T = T @ dh_transform(q[i - 1], robot.d[i], robot.a[i], robot.alpha[i])
    return T
""",
        mistake="shifted by one joint",
    ),
    Variant(
        "2.2",
        "float32, the flange 3 µm off",
        """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for i in range(6):
        T = T @ dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i])
    T[:3, 3] += 3e-6
    return T.astype(np.float32)
""",
        also=(("dh_transform", _DH_FLOAT32),),
    ),
    Variant(
        "2.2",
        "float64 product of a float32 dh_transform, the flange 3 µm off",
        """
def forward_kinematics(robot, q):
    T = np.eye(4)
    for i in range(6):
        T = T @ dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i])
    T[:3, 3] += 3e-6
    return T
""",
        also=(("dh_transform", _DH_FLOAT32),),
    ),
    Variant(
        "2.2",
        "calls urkin.fk",
        "def forward_kinematics(robot, q):\n    return urkin.fk(robot, q)\n",
        points=0,
    ),
    Variant(
        "2.2",
        "urkin's PoE product instead",
        """
def forward_kinematics(robot, q):
    S, M = urkin.poe.space_screws(robot)
    return urkin.poe.fk_space(M, S, q)
""",
        points=0,
    ),
    Variant(
        "2.2",
        "the last of urkin's frames",
        "def forward_kinematics(robot, q):\n    return urkin.fk_frames(robot, q)[-1]\n",
        points=0,
    ),
    Variant(
        "2.3",
        "seed 002's published formula",
        """
def ur5_position(q):
    d1, a2, a3, d4, d5, d6 = urkin.robot("UR5").lengths
    q1, q2, q3, q4, q5, _ = q
    c1, s1, c5, s5 = np.cos(q1), np.sin(q1), np.cos(q5), np.sin(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)
    return np.array([
        c1 * reach + d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234),
        s1 * reach - d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234),
        d1 + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5,
    ])
""",
        points=2,
        mistake="lack the factor sin q5",
    ),
    Variant(
        "2.3",
        "a product of the student's own DH matrices",
        """
def ur5_position(q):
    return forward_kinematics(urkin.robot("UR5"), q)[:3, 3]
""",
        points=3,
        mistake="product of DH matrices instead of the closed-form",
    ),
    Variant(
        "2.3",
        "urkin's symbolic T06 lambdified",
        """
def ur5_position(q):
    T = urkin.symbolic.ur_t06()
    f = sp.lambdify((Q, LENGTHS), T[:3, 3], "numpy")
    return np.asarray(f(q, urkin.robot("UR5").lengths), dtype=float).reshape(3)
""",
        points=0,
    ),
    Variant(
        "2.4",
        "float twists: cos(pi/2) = 6e-17 left in",
        """
def symbolic_fk(rows):
    q = sp.symbols(f"q1:{len(rows) + 1}")
    T = sp.eye(4)
    for qi, (d, a, alpha) in zip(q, rows):
        ca, sa, cq, sq = sp.cos(alpha), sp.sin(alpha), sp.cos(qi), sp.sin(qi)
        T = T * sp.Matrix([[cq, -sq * ca, sq * sa, a * cq], [sq, cq * ca, -cq * sa, a * sq],
                           [0, sa, ca, d], [0, 0, 0, 1]])
    return T
""",
        points=4,
        mistake="twists typed as floats",
    ),
    Variant(
        "2.4",
        "modified-DH link matrices",
        """
def symbolic_fk(rows):
    q = sp.symbols(f"q1:{len(rows) + 1}")
    T = sp.eye(4)
    for qi, (d, a, alpha) in zip(q, rows):
        k = round(alpha / (np.pi / 2))
        if abs(alpha / (np.pi / 2) - k) < 1e-12:
            alpha = k * sp.pi / 2
        ca, sa, cq, sq = sp.cos(alpha), sp.sin(alpha), sp.cos(qi), sp.sin(qi)
        T = (T * sp.Matrix([[cq, -sq, 0, a], [sq * ca, cq * ca, -sa, -sa * d],
                            [sq * sa, cq * sa, ca, ca * d], [0, 0, 0, 1]])).applyfunc(
            simplify_angles)
    return T
""",
        points=2,
        mistake="modified (Craig) DH",
    ),
    Variant(
        "2.4",
        "every twist rounded to a multiple of π/2",
        """
def symbolic_fk(rows):
    q = sp.symbols(f"q1:{len(rows) + 1}")
    T = sp.eye(4)
    for qi, (d, a, alpha) in zip(q, rows):
        alpha = round(alpha / (np.pi / 2)) * sp.pi / 2
        ca, sa, cq, sq = sp.cos(alpha), sp.sin(alpha), sp.cos(qi), sp.sin(qi)
        T = T * sp.Matrix([[cq, -sq * ca, sq * sa, a * cq], [sq, cq * ca, -cq * sa, a * sq],
                           [0, sa, ca, d], [0, 0, 0, 1]])
    return T
""",
        points=None,
    ),
    Variant(
        "2.4",
        "joint symbols numbered from 0",
        """
def symbolic_fk(rows):
    q = sp.symbols(f"q0:{len(rows)}")
    T = sp.eye(4)
    for qi, (d, a, alpha) in zip(q, rows):
        k = round(alpha / (np.pi / 2))
        if abs(alpha / (np.pi / 2) - k) < 1e-12:
            alpha = k * sp.pi / 2
        ca, sa, cq, sq = sp.cos(alpha), sp.sin(alpha), sp.cos(qi), sp.sin(qi)
        T = T * sp.Matrix([[cq, -sq * ca, sq * sa, a * cq], [sq, cq * ca, -cq * sa, a * sq],
                           [0, sa, ca, d], [0, 0, 0, 1]])
    return T
""",
        points=0,
        mistake="numbered from 1",
    ),
    Variant(
        "2.4",
        "numbers substituted for the joint angles",
        """
def symbolic_fk(rows):
    T = sp.eye(4)
    for d, a, alpha in rows:  # every joint at zero: a number, not a function of q
        T = T * sp.Matrix([[1, 0, 0, a], [0, np.cos(alpha), -np.sin(alpha), 0],
                           [0, np.sin(alpha), np.cos(alpha), d], [0, 0, 0, 1]])
    return T
""",
        points=0,
        mistake="replaced by numbers",
    ),
    Variant(
        "2.5",
        "a2 and a3 added with their signs",
        """
def upright_flange(robot):
    return np.array([0.0, -(robot.d4 + robot.d6), robot.d1 + robot.a2 + robot.a3 + robot.d5])
""",
        points=0,
        mistake="added with their signs",
    ),
    Variant(
        "2.5",
        "d6 counted as height",
        """
def upright_flange(robot):
    return np.array([0.0, -robot.d4, robot.d1 - robot.a2 - robot.a3 + robot.d5 + robot.d6])
""",
        points=0,
        mistake="d6 along z",
    ),
    Variant(
        "2.5",
        "computed with the student's forward kinematics",
        """
def upright_flange(robot):
    return forward_kinematics(robot, [0, -np.pi / 2, 0, -np.pi / 2, 0, 0])[:3, 3]
""",
        points=2,
        mistake="instead of predicted",
    ),
    Variant(
        "2.6",
        "rows copied unchanged, no tool",
        _to_modified(a="a", alpha="alpha", tool="np.eye(4)"),
        points=0,
        mistake="copied unchanged",
    ),
    Variant(
        "2.6",
        "a and α shifted up (a_(i+1))",
        _to_modified(a="np.r_[a[1:], 0.0]", alpha="np.r_[alpha[1:], 0.0]"),
        points=1,
        mistake="shifted the wrong way",
    ),
    Variant(
        "2.6",
        "α shifted, a kept",
        _to_modified(a="a"),
        points=1,
        mistake="α shifted but not a",
    ),
    Variant(
        "2.6",
        "a shifted, α kept, Tx(a_n) as the tool",
        _to_modified(alpha="alpha", tool="make_transform(p=[a[-1], 0, 0])"),
        points=0,
        mistake="a shifted but not α",
    ),
    Variant(
        "2.6",
        "d shifted with a and α",
        _to_modified(d="np.r_[0.0, d[:-1]]"),
        points=1,
        mistake="d shifted too",
    ),
    Variant(
        "2.6",
        "the tool transform forgotten",
        _to_modified(tool="np.eye(4)"),
        points=1,
        mistake="tool transform forgotten",
    ),
    Variant(
        "2.6",
        "the tool transform inverted",
        _to_modified(
            tool="np.linalg.inv(make_transform(p=[a[-1], 0, 0]) @ make_transform(rot_x(alpha[-1])))"
        ),
        points=1,
        mistake="T_tool inverted",
    ),
    Variant(
        "2.7",
        "only q = 0 tested",
        """
def formula_gap(formula, robot, n=1000, seed=0):
    q = np.zeros(6)
    return float(np.linalg.norm(formula(robot, q) - urkin.fk(robot, q)[:3, 3])), q
""",
        points=0,
        mistake="only q = 0 tested",
    ),
    Variant(
        "2.7",
        "a fixed handful of poses",
        """
def formula_gap(formula, robot, n=1000, seed=0):
    poses = [np.zeros(6), np.full(6, 0.35), np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])]
    gaps = [np.linalg.norm(formula(robot, q) - urkin.fk(robot, q)[:3, 3]) for q in poses]
    return max(gaps), poses[int(np.argmax(gaps))]
""",
        points=0,
        mistake="not one of the drawn configurations",
    ),
    Variant(
        "2.7",
        "the mean distance",
        _formula_gap(answer="distances.mean(), q[np.argmax(distances)]"),
        points=1,
        mistake="mean distance instead of the largest",
    ),
    Variant(
        "2.7",
        "the configuration of the smallest distance",
        _formula_gap(answer="distances.max(), q[np.argmin(distances)]"),
        points=1,
        mistake="smallest distance (argmin)",
    ),
    Variant(
        "2.7",
        "the largest coordinate difference",
        _formula_gap(
            distances="np.abs(difference)",
            answer="distances.max(), q[np.unravel_index(np.argmax(distances), distances.shape)[0]]",
        ),
        points=1,
        mistake="largest single coordinate",
    ),
    Variant(
        "2.7",
        "angles drawn in degrees",
        """
def formula_gap(formula, robot, n=1000, seed=0):
    q = np.random.default_rng(seed).uniform(-180.0, 180.0, (n, 6))
    distances = [np.linalg.norm(formula(robot, q_k) - forward_kinematics(robot, q_k)[:3, 3])
                 for q_k in q]
    return max(distances), q[int(np.argmax(distances))]
""",
        points=0,
        mistake="drawn in degrees",
    ),
    Variant(
        "2.7",
        "the draw converted with np.radians",
        _formula_gap(draw="np.radians(np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6)))"),
        points=0,
        mistake="converted with np.radians",
    ),
    Variant(
        "2.7",
        "the legacy np.random.seed",
        _formula_gap(draw="np.random.seed(seed) or np.random.uniform(-np.pi, np.pi, (n, 6))"),
        points=0,
        mistake="legacy np.random.seed",
    ),
]
