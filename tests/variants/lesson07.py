"""Lesson 07: other correct ways to write the exercises, and the usual mistakes."""

from tests.variants import Variant

# ---------------------------------------------------------------------------------- helpers

# ik_lab written out in one function (no lab_theta1, no planar_2r), the sheet's way with its
# mistakes switchable; the default is right.
_INLINE_IK = """
def _inline_ik(x_w, y_w, z_w, yaw_w, arctan=False, unsigned=False, arctan_hr=False,
               wrap=True, to_ur=True, elbow=1.0, plane=-1.0, tangent=-1.0):
    x, y, z = x_w + 0.15, y_w - 0.15, z_w - 0.01  # table → base frame
    x_c, y_c = x - 0.0535 * np.cos(yaw_w), y - 0.0535 * np.sin(yaw_w)
    heading = np.arctan(y_c / x_c) if arctan else np.arctan2(y_c, x_c)
    theta1 = heading + tangent * np.arcsin(0.110 / np.sqrt(x_c**2 + y_c**2))
    x3 = x_c - 0.083 * np.cos(theta1) + 0.110 * np.sin(theta1)
    y3 = y_c - 0.083 * np.sin(theta1) - 0.110 * np.cos(theta1)
    r = np.sqrt(x3**2 + y3**2) if unsigned else x3 * np.cos(theta1) + y3 * np.sin(theta1)
    h = z + 0.141 - 0.152
    theta3 = elbow * np.arccos((r**2 + h**2 - 0.244**2 - 0.213**2) / (2 * 0.244 * 0.213))
    beta = np.arctan2(0.213 * np.sin(theta3), 0.244 + 0.213 * np.cos(theta3))
    if arctan_hr:
        theta2 = -(np.arctan(h / r) + beta)
    else:
        theta2 = np.arctan2(plane * h, r) - beta
    q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                  np.pi / 2 + theta1 - yaw_w])
    if to_ur:
        q = q + np.array([np.pi, 0.0, 0.0, -np.pi / 2, 0.0, 0.0])
    return np.arctan2(np.sin(q), np.cos(q)) if wrap else q
"""


def _ik(body: str) -> str:
    return _INLINE_IK + f"\n\ndef ik_lab(x_w, y_w, z_w, yaw_w):\n    {body}\n"


# ------------------------------------------------------------------------------------ 7.1

_WRIST = """
def wrist_angles(T, theta1):
    T = np.asarray(T, dtype=float)
    x, y, z = T[:3, 0], T[:3, 1], T[:3, 2]
    z1 = np.array([np.sin(theta1), -np.cos(theta1), 0.0])
    a, b = x @ z1, -(y @ z1)
    theta5 = np.arctan2(np.hypot(a, b), z @ z1)
    theta6 = np.arctan2(b, a)
    return np.array([[theta5, theta6], [-theta5, theta6 + np.pi]])
"""

CORRECT = [
    # ------------------------------------------------------------------------------ 7.4
    Variant(
        "7.4",
        "from the flange axis in frame 1 (R01ᵀ z), lists, θ6 + π left unwrapped",
        """
def wrist_angles(T, theta1):
    R = np.array(T, dtype=float)[:3, :3]
    c1, s1 = np.cos(theta1), np.sin(theta1)
    R01 = np.array([[c1, 0.0, s1], [s1, 0.0, -c1], [0.0, 1.0, 0.0]])
    R16 = R01.T @ R  # the flange seen from frame 1: its z row is z1 · (x, y, z)
    sin5 = np.hypot(R16[2, 0], R16[2, 1])
    t5 = np.arctan2(sin5, R16[2, 2])
    t6 = np.arctan2(-R16[2, 1], R16[2, 0])
    return [[t5, t6], [-t5, t6 + np.pi]]
""",
    ),
    Variant(
        "7.1",
        "math module",
        """
import math

def lab_theta1(x_c, y_c):
    return math.atan2(y_c, x_c) - math.asin(0.110 / math.hypot(x_c, y_c))
""",
    ),
    Variant(
        "7.1",
        "arccos form of the tangent",
        """
def lab_theta1(x_c, y_c):
    rho = np.sqrt(x_c**2 + y_c**2)
    return np.arctan2(y_c, x_c) + np.arccos(OFFSET / rho) - np.pi / 2
""",
    ),
    Variant(
        "7.1",
        "atan2 of the right triangle's sides",
        """
def lab_theta1(x_c, y_c):
    along = np.sqrt(x_c * x_c + y_c * y_c - OFFSET * OFFSET)  # base to the foot of the offset
    return np.arctan2(y_c, x_c) - np.arctan2(OFFSET, along)
""",
    ),
    Variant(
        "7.1",
        "u from (x_c, y_c) = s u + 0.110 n, solved",
        """
def lab_theta1(x_c, y_c):
    d = L2 - L4 + L6
    s = np.sqrt(x_c**2 + y_c**2 - d**2)
    return np.arctan2(s * y_c - d * x_c, s * x_c + d * y_c)
""",
    ),
    Variant(
        "7.1",
        "wrapped into (−π, π]",
        """
def lab_theta1(x_c, y_c):
    return wrap_angles(np.arctan2(y_c, x_c) - np.arcsin(OFFSET / np.hypot(x_c, y_c)))
""",
    ),
    Variant(
        "7.1",
        "wrapped into [0, 2π) (no interval is asked)",
        """
def lab_theta1(x_c, y_c):
    return np.mod(np.arctan2(y_c, x_c) - np.arcsin(OFFSET / np.hypot(x_c, y_c)), 2 * np.pi)
""",
    ),
    Variant(
        "7.1",
        "float32",
        """
def lab_theta1(x_c, y_c):
    x, y = np.float32(x_c), np.float32(y_c)
    return np.arctan2(y, x) - np.arcsin(np.float32(0.110) / np.hypot(x, y))
""",
    ),
    Variant(
        "7.1",
        "degrees inside, radians out",
        """
def lab_theta1(x_c, y_c):
    theta_c = np.degrees(np.arctan2(y_c, x_c))
    theta_b = np.degrees(np.arcsin(OFFSET / np.hypot(x_c, y_c)))
    return np.radians(theta_c - theta_b)
""",
    ),
    # ------------------------------------------------------------------------------ 7.6
    Variant(
        "7.6",
        "a loop over solutions and joints, with math",
        """
def nearest_solution(solutions, q_current):
    import math
    if len(solutions) == 0:
        raise ValueError("no solutions to choose from")
    best, best_gap = None, math.inf
    for row in solutions:
        shifted = []
        for s, q in zip(row, q_current):
            s = s + 2 * math.pi * round((q - s) / (2 * math.pi))
            if s > 2 * math.pi:
                s -= 2 * math.pi
            if s < -2 * math.pi:
                s += 2 * math.pi
            shifted.append(s)
        gap = math.dist(shifted, q_current)
        if gap < best_gap:
            best, best_gap = shifted, gap
    return np.array(best)
""",
    ),
    Variant(
        "7.6",
        "wrapped differences added to q_current",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float)
    if solutions.size == 0:
        raise ValueError("the solutions array is empty")
    step = wrap_angles(solutions - q_current)
    shifted = q_current + step
    shifted = np.where(np.abs(shifted) > 2 * np.pi, shifted - np.sign(shifted) * 2 * np.pi, shifted)
    return shifted[np.argmin(np.linalg.norm(shifted - q_current, axis=1))]
""",
    ),
]

WRONG = [
    # ------------------------------------------------------------------------------ 7.4
    Variant(
        "7.4",
        "θ5 from arccos",
        _WRIST.replace(
            "theta5 = np.arctan2(np.hypot(a, b), z @ z1)",
            "theta5 = np.arccos(np.clip(z @ z1, -1.0, 1.0))",
        ),
        points=3,
        mistake="arccos",
    ),
    Variant(
        "7.4",
        "θ6 not turned by π",
        _WRIST.replace("[-theta5, theta6 + np.pi]", "[-theta5, theta6]"),
        points=0,
        mistake="turned by π",
    ),
    Variant(
        "7.4",
        "sign of y · z1",
        _WRIST.replace("a, b = x @ z1, -(y @ z1)", "a, b = x @ z1, y @ z1"),
        points=0,
        mistake="sign of y",
    ),
    Variant(
        "7.1",
        "the sheet's arctan(y/x)",
        """
def lab_theta1(x_c, y_c):
    return np.arctan(y_c / x_c) - np.arcsin(OFFSET / np.sqrt(x_c**2 + y_c**2))
""",
        points=1,
        mistake="arctan(y/x)",
    ),
    Variant(  # the old reference test's wrong variant
        "7.1",
        "arctan, the old test's variant",
        """
def lab_theta1(x, y):
    return np.arctan(y / x) - np.arcsin(0.110 / np.hypot(x, y))
""",
        points=1,
        mistake="arctan(y/x)",
    ),
    Variant(
        "7.1",
        "the other tangent (+ arcsin)",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) + np.arcsin(OFFSET / np.hypot(x_c, y_c))
""",
        points=0,
        mistake="other tangent",
    ),
    Variant(
        "7.1",
        "UR's joint 1 (+ π)",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) - np.arcsin(OFFSET / np.hypot(x_c, y_c)) + np.pi
""",
        points=0,
        mistake="UR's joint 1",
    ),
    Variant(
        "7.1",
        "degrees",
        """
def lab_theta1(x_c, y_c):
    return np.degrees(np.arctan2(y_c, x_c) - np.arcsin(OFFSET / np.hypot(x_c, y_c)))
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "7.1",
        "atan2(x, y)",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(x_c, y_c) - np.arcsin(OFFSET / np.hypot(x_c, y_c))
""",
        points=0,
        mistake="atan2(x, y)",
    ),
    Variant(
        "7.1",
        "the sheet's 110 mm",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) - np.arcsin(110 / np.sqrt(x_c**2 + y_c**2))
""",
        points=0,
        mistake="millimetres",
    ),
    Variant(
        "7.1",
        "the sheet's 110 mm, math module",
        """
import math

def lab_theta1(x_c, y_c):
    return math.atan2(y_c, x_c) - math.asin(110 / math.sqrt(x_c**2 + y_c**2))
""",
        points=0,
        mistake="millimetres",
    ),
    Variant(
        "7.1",
        "arccos for θB",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) - np.arccos(OFFSET / np.hypot(x_c, y_c))
""",
        points=0,
        mistake="arccos",
    ),
    Variant(
        "7.1",
        "θB forgotten",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c)
""",
        points=0,
        mistake="θB missing",
    ),
    Variant(
        "7.1",
        "arctan(0.110/ρ) for θB",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) - np.arctan(OFFSET / np.hypot(x_c, y_c))
""",
        points=0,
        mistake="arctan(0.110/ρ)",
    ),
    Variant(
        "7.1",
        "θB − θc",
        """
def lab_theta1(x_c, y_c):
    return np.arcsin(OFFSET / np.hypot(x_c, y_c)) - np.arctan2(y_c, x_c)
""",
        points=0,
        mistake="θB − θc",
    ),
    Variant(
        "7.1",
        "ρ² (no square root)",
        """
def lab_theta1(x_c, y_c):
    return np.arctan2(y_c, x_c) - np.arcsin(OFFSET / (x_c**2 + y_c**2))
""",
        points=0,
        mistake="ρ²",
    ),
]

# ------------------------------------------------------------------------------------ 7.2

CORRECT += [
    Variant(
        "7.2",
        "second law of cosines for θa (the sheet's way)",
        """
def planar_2r(x, y, l1, l2):
    d = np.hypot(x, y)
    theta_b = np.arccos(np.clip((d**2 - l1**2 - l2**2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arccos((l1**2 + d**2 - l2**2) / (2 * l1 * d))
    return np.array([theta_a, theta_b])
""",
    ),
    Variant(
        "7.2",
        "math module, clipped with min/max",
        """
import math

def planar_2r(x, y, l1, l2):
    c = (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    b = math.acos(max(-1.0, min(1.0, c)))
    a = math.atan2(y, x) - math.atan2(l2 * math.sin(b), l1 + l2 * math.cos(b))
    return np.array([a, b])
""",
    ),
    Variant(
        "7.2",
        "θb = atan2(√(1 − c²), c)",
        """
def planar_2r(x, y, l1, l2):
    c = np.clip((x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2), -1.0, 1.0)
    s = np.sqrt(1.0 - c * c)
    theta_b = np.arctan2(s, c)
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * s, l1 + l2 * c)
    return np.array([theta_a, theta_b])
""",
    ),
    Variant(
        "7.2",
        "complex numbers",
        """
def planar_2r(x, y, l1, l2):
    c = np.clip((abs(complex(x, y)) ** 2 - l1**2 - l2**2) / (2 * l1 * l2), -1, 1)
    b = np.arccos(c)
    a = np.angle(complex(x, y)) - np.angle(l1 + l2 * np.exp(1j * b))
    return np.array([a, b])
""",
    ),
    Variant(
        "7.2",
        "θa wrapped, returned as a tuple",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return wrap_angles(theta_a), theta_b
""",
    ),
    Variant(
        "7.2",
        "float32 angles returned as a tuple",
        """
def planar_2r(x, y, l1, l2):
    x, y, l1, l2 = (np.float32(v) for v in (x, y, l1, l2))
    b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(b), l1 + l2 * np.cos(b))
    return a, b
""",
    ),
    Variant(
        "7.2",
        "float32",
        """
def planar_2r(x, y, l1, l2):
    x, y, l1, l2 = (np.float32(v) for v in (x, y, l1, l2))
    cos_b = np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1)
    theta_b = np.arccos(cos_b)
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b], dtype=np.float32)
""",
    ),
]

WRONG += [
    Variant(
        "7.2",
        "arctan(y/x) for the tip's direction",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan(y / x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=2,
        mistake="arctan(y/x)",
    ),
    Variant(
        "7.2",
        "the other elbow",
        """
def planar_2r(x, y, l1, l2):
    theta_b = -np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=1,
        mistake="other elbow",
    ),
    Variant(
        "7.2",
        "the triangle's inner angle for θb",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((l1 * l1 + l2 * l2 - x * x - y * y) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=0,
        mistake="inner angle",
    ),
    Variant(
        "7.2",
        "+ atan2(…) for θa",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) + np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=1,
        mistake="the sign belongs to the other elbow",
    ),
    Variant(
        "7.2",
        "l1 and l2 swapped in atan2",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l1 * np.sin(theta_b), l2 + l1 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        mistake="swapped",
    ),
    Variant(
        "7.2",
        "atan2(x, y)",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(x, y) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=0,
        mistake="atan2(x, y)",
    ),
    Variant(
        "7.2",
        "degrees",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.degrees([theta_a, theta_b])
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "7.2",
        "arctan for the angle at the origin",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan(l2 * np.sin(theta_b) / (l1 + l2 * np.cos(theta_b)))
    return np.array([theta_a, theta_b])
""",
        mistake="arctan(l2 sin θb / (l1 + l2 cos θb))",
    ),
    Variant(
        "7.2",
        "θa = atan2(y, x)",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    return np.array([np.arctan2(y, x), theta_b])
""",
        mistake="θa = atan2(y, x)",
    ),
    Variant(
        "7.2",
        "[θb, θa]",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_b, theta_a])
""",
        points=0,
        mistake="[θb, θa]",
    ),
    Variant(
        "7.2",
        "cos θb not clipped",
        """
def planar_2r(x, y, l1, l2):
    theta_b = np.arccos((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2))
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=3,
        mistake="not clipped",
    ),
    Variant(
        "7.2",
        "math.acos, not clipped",
        """
import math

def planar_2r(x, y, l1, l2):
    theta_b = math.acos((x**2 + y**2 - l1**2 - l2**2) / (2 * l1 * l2))
    theta_a = math.atan2(y, x) - math.atan2(l2 * math.sin(theta_b), l1 + l2 * math.cos(theta_b))
    return np.array([theta_a, theta_b])
""",
        points=3,
        mistake="not clipped",
    ),
]

# ------------------------------------------------------------------------------------ 7.3

_PLANAR_2R_FLOAT32 = """
def planar_2r(x, y, l1, l2):
    x, y, l1, l2 = (np.float32(v) for v in (x, y, l1, l2))
    cos_b = np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1)
    theta_b = np.arccos(cos_b)
    theta_a = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta_b), l1 + l2 * np.cos(theta_b))
    return np.array([theta_a, theta_b], dtype=np.float32)
"""

_IK_LAB_FLOAT64 = """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    c1, s1 = np.cos(theta1), np.sin(theta1)
    x3, y3 = x_c - L7 * c1 + OFFSET * s1, y_c - L7 * s1 - OFFSET * c1
    r = x3 * c1 + y3 * s1
    h = z + L8 + L10 - L1
    theta2, theta3 = planar_2r(r, -h, L3, L5)
    lab_angles = np.array(
        [theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2, np.pi / 2 + theta1 - yaw_w],
        dtype=float,
    )
    return wrap_angles(lab_angles + LAB_TO_UR){shift}
"""

CORRECT += [
    Variant(
        "7.3",
        "float64 answer built on a float32 planar_2r (full marks in 7.2)",
        _IK_LAB_FLOAT64.format(shift=""),
        also=(("planar_2r", _PLANAR_2R_FLOAT32),),
    ),
    Variant(
        "7.3",
        "inlined, the sheet's numbers in metres",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w)"),
    ),
    Variant(
        "7.3",
        "the sheet's θ2 with atan2 and the signed r; np.mod wrap into (−π, π]",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = x_w - BASE_IN_TABLE[0], y_w - BASE_IN_TABLE[1], z_w - BASE_IN_TABLE[2]
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7  # n is at a right angle to u
    h = z + L8 + L10 - L1
    d = np.hypot(r, h)
    theta3 = np.arccos((r**2 + h**2 - L3**2 - L5**2) / (2 * L3 * L5))
    theta2 = -(np.arctan2(h, r) + np.arccos((L5**2 - L3**2 - d**2) / (-2 * L3 * d)))
    theta4 = -theta2 - theta3
    theta6 = np.pi / 2 - (yaw_w - theta1)
    q = np.array([theta1, theta2, theta3, theta4, -np.pi / 2, theta6]) + LAB_TO_UR
    return np.pi - np.mod(np.pi - q, 2 * np.pi)
""",
    ),
    Variant(
        "7.3",
        "math module, math.remainder wrap",
        """
import math

def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = x_w + 0.15, y_w - 0.15, z_w - 0.01
    x_c, y_c = x - L9 * math.cos(yaw_w), y - L9 * math.sin(yaw_w)
    t1 = lab_theta1(x_c, y_c)
    x3 = x_c - L7 * math.cos(t1) + OFFSET * math.sin(t1)
    y3 = y_c - L7 * math.sin(t1) - OFFSET * math.cos(t1)
    r = x3 * math.cos(t1) + y3 * math.sin(t1)
    h = z + L8 + L10 - L1
    t2, t3 = planar_2r(r, -h, L3, L5)
    lab = [t1, t2, t3, -t2 - t3, -math.pi / 2, math.pi / 2 + t1 - yaw_w]
    ur = [a + b for a, b in zip(lab, [math.pi, 0, 0, -math.pi / 2, 0, 0])]
    return np.array([math.remainder(a, 2 * math.pi) for a in ur])
""",
    ),
    Variant(
        "7.3",
        "float32 answer",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w]) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    c1, s1 = np.cos(theta1), np.sin(theta1)
    r = (x_c - L7 * c1 + OFFSET * s1) * c1 + (y_c - L7 * s1 - OFFSET * c1) * s1
    h = z + L8 + L10 - L1
    theta2, theta3 = planar_2r(r, -h, L3, L5)
    q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                  np.pi / 2 + theta1 - yaw_w]) + LAB_TO_UR
    return wrap_angles(q).astype(np.float32)
""",
    ),
    Variant(
        "7.3",
        "float32 throughout, arctan2(sin, cos) wrap",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    f = np.float32
    x, y, z = np.array([x_w, y_w, z_w], dtype=f) - BASE_IN_TABLE.astype(f)
    yaw = f(yaw_w)
    l1, l3, l5, l7, l8, l9, l10, off = (f(v) for v in (L1, L3, L5, L7, L8, L9, L10, OFFSET))
    x_c, y_c = x - l9 * np.cos(yaw), y - l9 * np.sin(yaw)
    theta1 = np.arctan2(y_c, x_c) - np.arcsin(off / np.hypot(x_c, y_c))
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - l7
    h = z + l8 + l10 - l1
    c3 = np.clip((r * r + h * h - l3 * l3 - l5 * l5) / (2 * l3 * l5), f(-1), f(1))
    theta3 = np.arccos(c3)
    theta2 = np.arctan2(-h, r) - np.arctan2(l5 * np.sin(theta3), l3 + l5 * np.cos(theta3))
    q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                  np.pi / 2 + theta1 - yaw], dtype=f) + LAB_TO_UR.astype(f)
    return np.arctan2(np.sin(q), np.cos(q))
""",
    ),
    Variant(
        "7.3",
        "a list of numbers",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = x_w - BASE_IN_TABLE[0], y_w - BASE_IN_TABLE[1], z_w - BASE_IN_TABLE[2]
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = [theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2, np.pi / 2 + theta1 - yaw_w]
    return [float(wrap_angles(a + b)) for a, b in zip(lab_q, LAB_TO_UR)]
""",
    ),
    Variant(
        "7.3",
        "through the lab robot's frames: wrist centre from a rotation",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    R_cup = rot_z(yaw_w) @ rot_x(np.pi)  # the gripper frame: z down, x along the plate
    cup = np.array([x_w, y_w, z_w]) - BASE_IN_TABLE
    centre = cup - L9 * R_cup[:, 0]  # back along the plate to the flange axis
    theta1 = lab_theta1(centre[0], centre[1])
    u = np.array([np.cos(theta1), np.sin(theta1)])
    r = centre[:2] @ u - L7
    h = centre[2] + L8 + L10 - L1
    theta2, theta3 = planar_2r(r, -h, L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
    ),
]

WRONG += [
    Variant(
        "7.3",
        "built on a float32 planar_2r, every angle 2e-5 rad off",
        _IK_LAB_FLOAT64.format(shift=" + 2e-5"),
        also=(("planar_2r", _PLANAR_2R_FLOAT32),),
        points=None,
        mistake=None,
    ),
    Variant(
        "7.3",
        "the sheet as printed (arctan, √(x² + y²), arctan(h/r)), wrapped",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, arctan=True, unsigned=True, arctan_hr=True)"),
        points=1,
        mistake="arctan(y/x)",
    ),
    Variant(
        "7.3",
        "arctan(y/x) for θ1",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, arctan=True)"),
        points=2,
        mistake="arctan(y/x)",
    ),
    Variant(
        "7.3",
        "unsigned r",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, unsigned=True)"),
        points=4,
        mistake="√(x² + y²)",
    ),
    Variant(
        "7.3",
        "arctan(h/r) in θ2",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, arctan_hr=True)"),
        points=4,
        mistake="arctan(h/r)",
    ),
    # the old test's three variants: the sheet's mistakes one at a time, angles unwrapped
    Variant(
        "7.3",
        "old: arctan, unwrapped",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, arctan=True, wrap=False)"),
        points=2,
        mistake="arctan(y/x)",
    ),
    Variant(
        "7.3",
        "old: √(x² + y²), unwrapped",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, unsigned=True, wrap=False)"),
        points=3,
        mistake="√(x² + y²)",
    ),
    Variant(
        "7.3",
        "old: arctan(h/r), unwrapped",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, arctan_hr=True, wrap=False)"),
        points=3,
        mistake="arctan(h/r)",
    ),
    Variant(
        "7.3",
        "lab angles returned",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, to_ur=False)"),
        points=0,
        mistake="lab angles",
    ),
    Variant(
        "7.3",
        "LAB_TO_UR subtracted",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q - LAB_TO_UR)
""",
        points=0,
        mistake="subtracted",
    ),
    Variant(
        "7.3",
        "degrees",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return np.degrees(wrap_angles(lab_q + LAB_TO_UR))
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "7.3",
        "the other elbow",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, elbow=-1.0)"),
        points=4,
        mistake="other elbow",
    ),
    Variant(
        "7.3",
        "the other tangent for θ1",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, tangent=1.0)"),
        points=0,
        mistake="other tangent",
    ),
    Variant(
        "7.3",
        "planar_2r on (r, h)",
        _ik("return _inline_ik(x_w, y_w, z_w, yaw_w, plane=1.0)"),
        points=0,
        mistake="planar_2r(r, h, …)",
    ),
    Variant(
        "7.3",
        "not wrapped",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    c1, s1 = np.cos(theta1), np.sin(theta1)
    x3, y3 = x_c - L7 * c1 + OFFSET * s1, y_c - L7 * s1 - OFFSET * c1
    theta2, theta3 = planar_2r(x3 * c1 + y3 * s1, -(z + L8 + L10 - L1), L3, L5)
    return np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                     np.pi / 2 + theta1 - yaw_w]) + LAB_TO_UR
""",
        points=4,
        mistake="not wrapped",
    ),
    Variant(
        "7.3",
        "wrapped before adding LAB_TO_UR",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    c1, s1 = np.cos(theta1), np.sin(theta1)
    x3, y3 = x_c - L7 * c1 + OFFSET * s1, y_c - L7 * s1 - OFFSET * c1
    theta2, theta3 = planar_2r(x3 * c1 + y3 * s1, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q) + LAB_TO_UR
""",
        points=4,
        mistake="not wrapped",
    ),
    Variant(
        "7.3",
        "wrapped into [0, 2π)",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    c1, s1 = np.cos(theta1), np.sin(theta1)
    x3, y3 = x_c - L7 * c1 + OFFSET * s1, y_c - L7 * s1 - OFFSET * c1
    theta2, theta3 = planar_2r(x3 * c1 + y3 * s1, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return np.mod(lab_q + LAB_TO_UR, 2 * np.pi)
""",
        points=4,
        mistake="[0, 2π)",
    ),
    Variant(
        "7.3",
        "the sheet's millimetres",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = x_w + 0.15, y_w - 0.15, z_w - 0.01
    x_c, y_c = x - 0.0535 * np.cos(yaw_w), y - 0.0535 * np.sin(yaw_w)
    theta1 = np.arctan2(y_c, x_c) - np.arcsin(110 / np.sqrt(x_c**2 + y_c**2))
    x3 = x_c - 83 * np.cos(theta1) + 110 * np.sin(theta1)
    y3 = y_c - 83 * np.sin(theta1) - 110 * np.cos(theta1)
    r = x3 * np.cos(theta1) + y3 * np.sin(theta1)
    theta2, theta3 = planar_2r(r, -(z + 141 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="millimetres",
    ),
    Variant(
        "7.3",
        "BASE_IN_TABLE not subtracted",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x_c, y_c = x_w - L9 * np.cos(yaw_w), y_w - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z_w + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="not subtracted",
    ),
    Variant(
        "7.3",
        "the cup as the wrist centre",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    theta1 = lab_theta1(x, y)
    r = x * np.cos(theta1) + y * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="the cup used as the wrist centre",
    ),
    Variant(
        "7.3",
        "h without L10",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="without L10",
    ),
    Variant(
        "7.3",
        "h without L1",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="without − L1",
    ),
    Variant(
        "7.3",
        "r without the step back L7",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1)
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="step back L7",
    ),
    Variant(
        "7.3",
        "θ6 = ψ − θ1 − π/2",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, -np.pi / 2,
                      yaw_w - theta1 - np.pi / 2])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="θ6",
    ),
    Variant(
        "7.3",
        "θ5 = +π/2",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    x, y, z = np.array([x_w, y_w, z_w], dtype=float) - BASE_IN_TABLE
    x_c, y_c = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    theta1 = lab_theta1(x_c, y_c)
    r = x_c * np.cos(theta1) + y_c * np.sin(theta1) - L7
    theta2, theta3 = planar_2r(r, -(z + L8 + L10 - L1), L3, L5)
    lab_q = np.array([theta1, theta2, theta3, -theta2 - theta3, np.pi / 2,
                      np.pi / 2 + theta1 - yaw_w])
    return wrap_angles(lab_q + LAB_TO_UR)
""",
        points=0,
        mistake="θ5 = +π/2",
    ),
    Variant(
        "7.3",
        "urkin's ik_lab (hidden)",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    return urkin.course.lab.ik_lab(x_w, y_w, z_w, yaw_w)
""",
        points=0,
    ),
    Variant(
        "7.3",
        "row 2 of urkin.ik_analytic (hidden)",
        """
def ik_lab(x_w, y_w, z_w, yaw_w):
    return urkin.ik_analytic(lab, gripper_pose(x_w, y_w, z_w, yaw_w))[2]
""",
        points=0,
    ),
]

# ------------------------------------------------------------------------------------ 7.5

_COUNT = """
def solution_count(robot, T):
    T = np.asarray(T, dtype=float)
    z = T[:3, 2]
    wrist = T[:3, 3] - robot.d6 * z
    rho = np.hypot(wrist[0], wrist[1])
    if rho < robot.d4:
        return 0
    shortest, longest = abs(abs(robot.a2) - abs(robot.a3)), abs(robot.a2) + abs(robot.a3)
    count = 0
    for side in (1.0, -1.0):
        theta1 = np.arctan2(wrist[1], wrist[0]) + side * np.arccos(robot.d4 / rho) + np.pi / 2
        z1 = np.array([np.sin(theta1), -np.cos(theta1), 0.0])
        u = np.array([np.cos(theta1), np.sin(theta1), 0.0])
        link = np.cross(z1, z)
        link /= np.linalg.norm(link)
        for flip in (1.0, -1.0):
            wrist1 = wrist - flip * robot.d5 * link
            reach = np.hypot(u @ wrist1, wrist1[2] - robot.d1)
            if shortest <= reach <= longest:
                count += 2
    return count
"""

CORRECT += [
    Variant(
        "7.5",
        "the lesson's recipe: your wrist_angles, then θ234 and (r, h) of step 4",
        """
def solution_count(robot, T):
    T = np.asarray(T, dtype=float)
    d1, a2, a3, d4, d5, d6 = robot.d1, robot.a2, robot.a3, robot.d4, robot.d5, robot.d6
    c = T[:3, 3] - d6 * T[:3, 2]
    rho = np.hypot(c[0], c[1])
    if rho < d4:
        return 0
    x_z, y_z, z_z = T[2, :3]
    count = 0
    for sign in (1, -1):
        theta1 = np.arctan2(c[1], c[0]) + sign * np.arccos(d4 / rho) + np.pi / 2
        for theta5, theta6 in wrist_angles(T, theta1):
            c5, s5, c6, s6 = np.cos(theta5), np.sin(theta5), np.cos(theta6), np.sin(theta6)
            q234 = np.arctan2(c5 * (c6 * x_z - s6 * y_z) - s5 * z_z, s6 * x_z + c6 * y_z)
            r = np.cos(theta1) * c[0] + np.sin(theta1) * c[1] - d5 * np.sin(q234)
            h = c[2] - d1 + d5 * np.cos(q234)
            cos3 = (r * r + h * h - a2 * a2 - a3 * a3) / (2 * a2 * a3)
            if abs(cos3) <= 1:
                count += 2
    return count
""",
    ),
    Variant(
        "7.5",
        "math module, wrist 1's distance from the shoulder axis as a line in space",
        """
import math


def solution_count(robot, T):
    rows = [[float(v) for v in row] for row in np.asarray(T)]
    z = [rows[0][2], rows[1][2], rows[2][2]]
    c = [rows[i][3] - robot.d6 * z[i] for i in range(3)]
    rho = math.hypot(c[0], c[1])
    if rho < robot.d4:
        return 0
    lo, hi = abs(abs(robot.a2) - abs(robot.a3)), abs(robot.a2) + abs(robot.a3)
    total = 0
    for theta1 in (math.atan2(c[1], c[0]) + s * math.acos(robot.d4 / rho) + math.pi / 2
                   for s in (1, -1)):
        axis = [math.sin(theta1), -math.cos(theta1), 0.0]  # the shoulder axis, through (0, 0, d1)
        link = [axis[1] * z[2] - axis[2] * z[1], axis[2] * z[0] - axis[0] * z[2],
                axis[0] * z[1] - axis[1] * z[0]]
        size = math.sqrt(sum(v * v for v in link))
        for flip in (1, -1):
            point = [c[i] - flip * robot.d5 * link[i] / size for i in range(3)]
            rel = [point[0], point[1], point[2] - robot.d1]
            along = sum(a * b for a, b in zip(rel, axis))
            distance = math.sqrt(max(sum(v * v for v in rel) - along * along, 0.0))
            total += 2 * (lo <= distance <= hi)
    return total
""",
    ),
    Variant(
        "7.5",
        "the four branches as arrays, a numpy integer returned",
        """
def solution_count(robot, T):
    T = np.asarray(T, dtype=float)
    z = T[:3, 2]
    c = T[:3, 3] - robot.d6 * z
    rho = np.hypot(*c[:2])
    if rho <= robot.d4:
        return np.int64(0)
    theta1 = np.arctan2(c[1], c[0]) + np.array([1, 1, -1, -1]) * np.arccos(robot.d4 / rho)
    theta1 = theta1 + np.pi / 2
    z1 = np.stack([np.sin(theta1), -np.cos(theta1), np.zeros(4)], axis=1)
    link = np.cross(z1, z)
    link /= np.linalg.norm(link, axis=1, keepdims=True)
    wrist1 = c - robot.d5 * np.array([1, -1, 1, -1])[:, None] * link
    r = np.cos(theta1) * wrist1[:, 0] + np.sin(theta1) * wrist1[:, 1]
    d = np.hypot(r, wrist1[:, 2] - robot.d1)
    closes = (d >= abs(abs(robot.a2) - abs(robot.a3))) & (d <= abs(robot.a2) + abs(robot.a3))
    return 2 * np.count_nonzero(closes)
""",
    ),
]

WRONG += [
    Variant(
        "7.5",
        "always 8",
        "def solution_count(robot, T):\n    return 8\n",
        points=0,
        mistake="always 8",
    ),
    Variant(
        "7.5",
        "the elbow triangle not checked",
        _COUNT.replace("if shortest <= reach <= longest:", "if True:"),
        points=1,
        mistake="the elbow triangle not checked",
    ),
    Variant(
        "7.5",
        "the cylinder not checked: arccos clipped",
        _COUNT.replace("    if rho < robot.d4:\n        return 0\n", "").replace(
            "np.arccos(robot.d4 / rho)", "np.arccos(np.clip(robot.d4 / rho, -1.0, 1.0))"
        ),
        points=2,
        mistake="the d4 cylinder not checked",
    ),
    Variant(
        "7.5",
        "one triangle per θ1, counted for both θ5",
        _COUNT.replace("wrist - flip * robot.d5 * link", "wrist - robot.d5 * link"),
        points=2,
        mistake="the elbow decided once per θ1",
    ),
    Variant(
        "7.5",
        "the two elbows not counted",
        _COUNT.replace("count += 2", "count += 1"),
        points=0,
        mistake="the two elbows not counted",
    ),
    Variant(
        "7.5",
        "only θ1 counted",
        """
def solution_count(robot, T):
    T = np.asarray(T, dtype=float)
    wrist = T[:3, 3] - robot.d6 * T[:3, 2]
    return 2 if np.hypot(wrist[0], wrist[1]) >= robot.d4 else 0
""",
        points=0,
        mistake="only the θ1 tangents counted",
    ),
    Variant(
        "7.5",
        "d1 left out",
        _COUNT.replace("wrist1[2] - robot.d1", "wrist1[2]"),
        points=None,
        mistake="d1 left out",
    ),
    Variant(
        "7.5",
        "the flange position as the wrist point",
        _COUNT.replace("wrist = T[:3, 3] - robot.d6 * z", "wrist = T[:3, 3]"),
        points=None,
        mistake="the flange position p",
    ),
    Variant(
        "7.5",
        "urkin.ik_analytic (hidden)",
        "def solution_count(robot, T):\n    return len(urkin.ik_analytic(robot, T))\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 7.6
    Variant(
        "7.6",
        "returned wrapped",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float)
    if len(solutions) == 0:
        raise ValueError("solutions is empty")
    gaps = np.linalg.norm(wrap_angles(solutions - q_current), axis=1)
    return solutions[np.argmin(gaps)]
""",
        points=1,
        mistake="returned wrapped",
    ),
    Variant(
        "7.6",
        "nearest by the sum of the differences' sizes",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float)
    if len(solutions) == 0:
        raise ValueError("solutions is empty")
    q = np.asarray(q_current, dtype=float)
    shifted = solutions + 2 * np.pi * np.round((q - solutions) / (2 * np.pi))
    shifted = np.where(shifted > 2 * np.pi, shifted - 2 * np.pi, shifted)
    shifted = np.where(shifted < -2 * np.pi, shifted + 2 * np.pi, shifted)
    return shifted[np.argmin(np.abs(shifted - q).sum(axis=1))]
""",
        points=None,
        mistake="(L1)",
    ),
    Variant(
        "7.6",
        "limits ignored",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float)
    if len(solutions) == 0:
        raise ValueError("solutions is empty")
    shifted = solutions + 2 * np.pi * np.round((q_current - solutions) / (2 * np.pi))
    return shifted[np.argmin(np.linalg.norm(shifted - q_current, axis=1))]
""",
        points=3,
        mistake="limits ignored",
    ),
    Variant(
        "7.6",
        "plain distance",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float)
    if len(solutions) == 0:
        raise ValueError("solutions is empty")
    return solutions[np.argmin(np.linalg.norm(solutions - q_current, axis=1))]
""",
        points=None,
        mistake=None,
    ),
    Variant(
        "7.6",
        "argmin of an empty array",
        """
def nearest_solution(solutions, q_current):
    solutions = np.asarray(solutions, dtype=float).reshape(-1, 6)
    shifted = solutions + 2 * np.pi * np.round((q_current - solutions) / (2 * np.pi))
    shifted = np.where(shifted > 2 * np.pi, shifted - 2 * np.pi, shifted)
    shifted = np.where(shifted < -2 * np.pi, shifted + 2 * np.pi, shifted)
    return shifted[np.argmin(np.linalg.norm(shifted - q_current, axis=1))]
""",
        points=3,
        mistake="not a ValueError naming solutions",
    ),
]
