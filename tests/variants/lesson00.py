"""Lesson 00: other correct ways to write its exercises, and known mistakes."""

from tests.variants import Variant

CORRECT = [
    # ------------------------------------------------------------------ 0.1 deg_to_rad
    Variant(
        "0.1", "np.radians", "def deg_to_rad(angles_deg):\n    return np.radians(angles_deg)\n"
    ),
    Variant(
        "0.1",
        "np.deg2rad of np.asarray",
        "def deg_to_rad(angles_deg):\n    return np.deg2rad(np.asarray(angles_deg))\n",
    ),
    Variant(
        "0.1",
        "math for one number, numpy for the rest",
        "import math\n\n"
        "def deg_to_rad(angles_deg):\n"
        "    if isinstance(angles_deg, (int, float)):\n"
        "        return math.radians(angles_deg)\n"
        "    return np.asarray(angles_deg, dtype=float) * (math.pi / 180)\n",
    ),
    Variant(
        "0.1",
        "float32 arrays",
        "def deg_to_rad(angles_deg):\n"
        "    return np.asarray(angles_deg, dtype=np.float32) * np.float32(np.pi / 180)\n",
    ),
    Variant(
        "0.1",
        "2π/360, divided last",
        "def deg_to_rad(angles_deg):\n"
        "    return np.array(angles_deg, dtype=float) * 2 * np.pi / 360\n",
    ),
    Variant(
        "0.1",
        "explicit loop over every index",
        "import math\n\n"
        "def deg_to_rad(angles_deg):\n"
        "    a = np.asarray(angles_deg, dtype=float)\n"
        "    out = np.empty_like(a)\n"
        "    for index in np.ndindex(a.shape):\n"
        "        out[index] = a[index] * math.pi / 180.0\n"
        "    return out\n",
    ),
    Variant(
        "0.1",
        "np.multiply with a module constant and a helper",
        "DEG = np.pi / 180.0\n\n"
        "def _scale(values, factor):\n"
        "    return np.multiply(values, factor)\n\n"
        "def deg_to_rad(angles_deg):\n"
        "    return _scale(angles_deg, DEG)\n",
    ),
    Variant(
        "0.1",
        "an assert on finite input, then / 180 * π",
        "def deg_to_rad(angles_deg):\n"
        "    a = np.asarray(angles_deg, dtype=float)\n"
        "    assert np.all(np.isfinite(a)), 'angles must be finite'\n"
        "    return a / 180.0 * np.pi\n",
    ),
    Variant(
        "0.1",
        "lists recursively, numbers and arrays directly",
        "def deg_to_rad(angles_deg):\n"
        "    if isinstance(angles_deg, (list, tuple)):\n"
        "        return [deg_to_rad(a) for a in angles_deg]\n"
        "    return angles_deg * np.pi / 180.0\n",
    ),
    Variant(
        "0.1",
        "the full-precision literal of π/180",
        "def deg_to_rad(angles_deg):\n"
        "    return np.asarray(angles_deg, dtype=float) * 0.017453292519943295\n",
    ),
    Variant(
        "0.1",
        "NotImplementedError for strings only",
        "def deg_to_rad(angles_deg):\n"
        "    if isinstance(angles_deg, str):\n"
        "        raise NotImplementedError('angles are numbers')\n"
        "    return np.asarray(angles_deg, dtype=float) * (np.pi / 180.0)\n",
    ),
    # -------------------------------------------------------------- 0.2 base_link_pose
    Variant(
        "0.2",
        "x and y rows negated",
        "def base_link_pose(T_base_tool):\n"
        "    T = np.array(T_base_tool, dtype=float)\n"
        "    T[:2] *= -1.0\n"
        "    return T\n",
    ),
    Variant(
        "0.2",
        "urkin's rot_z(π) and make_transform",
        "def base_link_pose(T_base_tool):\n"
        "    T_bl_b = urkin.transforms.make_transform(urkin.transforms.rot_z(np.pi))\n"
        "    return T_bl_b @ T_base_tool\n",
    ),
    Variant(
        "0.2",
        "Rz(π) typed from cos and sin",
        "def base_link_pose(T_base_tool):\n"
        "    c, s = np.cos(np.pi), np.sin(np.pi)\n"
        "    T_base_link_base = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0],"
        " [0, 0, 0, 1]])\n"
        "    return np.dot(T_base_link_base, T_base_tool)\n",
    ),
    Variant(
        "0.2",
        "rotation and position turned separately",
        "def base_link_pose(T_base_tool):\n"
        "    Rz = np.diag([-1.0, -1.0, 1.0])\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = Rz @ T_base_tool[:3, :3]\n"
        "    out[:3, 3] = Rz @ T_base_tool[:3, 3]\n"
        "    return out\n",
    ),
    Variant(
        "0.2",
        "float32",
        "def base_link_pose(T_base_tool):\n"
        "    flip = np.diag([-1.0, -1.0, 1.0, 1.0]).astype(np.float32)\n"
        "    return flip @ np.asarray(T_base_tool, dtype=np.float32)\n",
    ),
    Variant(
        "0.2",
        "explicit triple loop",
        "def base_link_pose(T_base_tool):\n"
        "    A = [[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]\n"
        "    out = np.zeros((4, 4))\n"
        "    for i in range(4):\n"
        "        for j in range(4):\n"
        "            for k in range(4):\n"
        "                out[i, j] += A[i][k] * T_base_tool[k][j]\n"
        "    return out\n",
    ),
    Variant(
        "0.2",
        "an assert on the shape",
        "def base_link_pose(T_base_tool):\n"
        "    T_base_tool = np.asarray(T_base_tool)\n"
        "    assert T_base_tool.shape == (4, 4)\n"
        "    return np.diag([-1.0, -1.0, 1.0, 1.0]) @ T_base_tool\n",
    ),
    # ---------------------------------------------------------------- 0.3 turn_joint1
    Variant(
        "0.3",
        "rotation and position turned separately, explicit c and s",
        "def turn_joint1(T_base_flange, angle):\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    Rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = Rz @ T_base_flange[:3, :3]\n"
        "    out[:3, 3] = Rz @ T_base_flange[:3, 3]\n"
        "    return out\n",
    ),
    Variant(
        "0.3",
        "urkin's rot_z and make_transform",
        "def turn_joint1(T_base_flange, angle):\n"
        "    turn = urkin.transforms.make_transform(urkin.transforms.rot_z(angle))\n"
        "    return turn @ T_base_flange\n",
    ),
    Variant(
        "0.3",
        "the angle wrapped into [0, 2π) first",
        "def turn_joint1(T_base_flange, angle):\n"
        "    angle = np.mod(angle, 2 * np.pi)\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    Rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return np.dot(Rz, T_base_flange)\n",
    ),
    Variant(
        "0.3",
        "x and y rows mixed by hand",
        "def turn_joint1(T_base_flange, angle):\n"
        "    T = np.array(T_base_flange, dtype=float)\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    x, y = T[0].copy(), T[1].copy()\n"
        "    T[0], T[1] = c * x - s * y, s * x + c * y\n"
        "    return T\n",
    ),
    Variant(
        "0.3",
        "float32",
        "def turn_joint1(T_base_flange, angle):\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    Rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return (Rz @ T_base_flange).astype(np.float32)\n",
    ),
]

WRONG = [
    # ------------------------------------------------------------------ 0.1 deg_to_rad
    Variant(
        "0.1",
        "unchanged",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=float)\n",
        points=0,
        mistake="unchanged",
    ),
    Variant(
        "0.1",
        "the wrong way",
        "def deg_to_rad(angles_deg):\n    return np.degrees(angles_deg)\n",
        points=0,
        mistake="wrong way",
    ),
    Variant(
        "0.1",
        "seed 002's 0.0175",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=float) * 0.0175\n",
        points=0,
        mistake="0.0175",
    ),
    Variant(
        "0.1",
        "seed 002's 0.01744",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=float) * 0.01744\n",
        points=0,
        mistake="0.01744",
    ),
    Variant(
        "0.1",
        "divided by 180 only",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=float) / 180\n",
        points=0,
        mistake="without multiplying by π",
    ),
    Variant(
        "0.1",
        "3.14 for π",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, float) * 3.14 / 180\n",
        points=0,
        mistake="rounded factor",
    ),
    Variant(
        "0.1",
        "divided by 57.3",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=float) / 57.3\n",
        points=0,
        mistake="rounded factor",
    ),
    Variant(
        "0.1",
        "π/180 to ten digits",
        "def deg_to_rad(angles_deg):\n"
        "    return np.asarray(angles_deg, dtype=float) * 0.0174532925\n",
        points=0,
        mistake="rounded factor",
    ),
    Variant(
        "0.1",
        "π/360",
        "def deg_to_rad(angles_deg):\n"
        "    return np.asarray(angles_deg, dtype=float) * np.pi / 360\n",
        points=0,
        mistake="the factor 0.00872665",
    ),
    Variant(
        "0.1",
        "result rounded to 4 decimals",
        "def deg_to_rad(angles_deg):\n    return np.round(np.radians(angles_deg), 4)\n",
        points=0,
        mistake="rounded (to 4 decimals)",
    ),
    Variant(
        "0.1",
        "math.radians on everything",
        "import math\n\ndef deg_to_rad(angles_deg):\n    return math.radians(angles_deg)\n",
        points=1,
        mistake="math.radians",
    ),
    Variant(
        "0.1",
        "a list multiplied like an array",
        "def deg_to_rad(angles_deg):\n    return angles_deg * np.pi / 180\n",
        points=4,
        mistake="list",
    ),
    Variant(
        "0.1",
        "in-place *= on the argument",
        "def deg_to_rad(angles_deg):\n    angles_deg *= np.pi / 180\n    return angles_deg\n",
        points=4,
        mistake="list",
    ),
    Variant(
        "0.1",
        "list methods on the argument",
        "def deg_to_rad(angles_deg):\n"
        "    if np.ndim(angles_deg) == 0:\n"
        "        return angles_deg * np.pi / 180\n"
        "    return angles_deg.astype(float) * np.pi / 180\n",
        points=4,
        mistake="array methods used on a list",
    ),
    Variant(
        "0.1",
        "a list comprehension",
        "import math\n\n"
        "def deg_to_rad(angles_deg):\n"
        "    return [a * math.pi / 180 for a in angles_deg]\n",
        points=4,
        mistake="loops over its input",
    ),
    Variant(
        "0.1",
        "math.radians in a comprehension",
        "import math\n\n"
        "def deg_to_rad(angles_deg):\n"
        "    return np.array([math.radians(a) for a in angles_deg])\n",
        points=3,
        mistake="loops over its input",
    ),
    Variant(
        "0.1",
        "wrapped into (−π, π]",
        "def deg_to_rad(angles_deg):\n"
        "    r = np.radians(angles_deg)\n"
        "    return np.arctan2(np.sin(r), np.cos(r))\n",
        mistake="wrapped into one turn",
    ),
    Variant(
        "0.1",
        "wrapped into [0, 2π)",
        "def deg_to_rad(angles_deg):\n    return np.mod(np.radians(angles_deg), 2 * np.pi)\n",
        mistake="[0, 2π)",
    ),
    Variant(
        "0.1",
        "flattened",
        "def deg_to_rad(angles_deg):\n    return np.ravel(angles_deg) * np.pi / 180\n",
        points=4,
        mistake="flattened",
    ),
    Variant(
        "0.1",
        "integer dtype",
        "def deg_to_rad(angles_deg):\n    return np.asarray(angles_deg, dtype=int) * np.pi / 180\n",
        points=1,
        mistake="whole degrees",
    ),
    Variant("0.1", "a constant", "def deg_to_rad(angles_deg):\n    return 0.0\n", points=0),
    Variant(
        "0.1",
        "NotImplementedError for lists",
        "def deg_to_rad(angles_deg):\n"
        "    if isinstance(angles_deg, list):\n"
        "        raise NotImplementedError('lists are not supported')\n"
        "    return np.radians(angles_deg)\n",
        points=4,
    ),
    # -------------------------------------------------------------- 0.2 base_link_pose
    Variant(
        "0.2",
        "wrong side",
        "def base_link_pose(T_base_tool):\n"
        "    return T_base_tool @ np.diag([-1.0, -1.0, 1.0, 1.0])\n",
        points=0,
        mistake="wrong side",
    ),
    Variant(
        "0.2",
        "x and y columns negated (the wrong side)",
        "def base_link_pose(T_base_tool):\n"
        "    T = T_base_tool.copy()\n"
        "    T[:, :2] *= -1\n"
        "    return T\n",
        points=0,
        mistake="wrong side",
    ),
    Variant(
        "0.2",
        "a quarter turn",
        "def base_link_pose(T_base_tool):\n"
        "    Rz = urkin.transforms.make_transform(urkin.transforms.rot_z(np.pi / 2))\n"
        "    return Rz @ T_base_tool\n",
        points=0,
        mistake="π/2 instead of π",
    ),
    Variant(
        "0.2",
        "unchanged",
        "def base_link_pose(T_base_tool):\n    return T_base_tool\n",
        points=0,
        mistake="unchanged",
    ),
    Variant(
        "0.2",
        "180 as radians",
        "def base_link_pose(T_base_tool):\n"
        "    c, s = np.cos(180), np.sin(180)\n"
        "    Rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return Rz @ T_base_tool\n",
        points=0,
        mistake="180",
    ),
    Variant(
        "0.2",
        "a half turn about x",
        "def base_link_pose(T_base_tool):\n"
        "    return np.diag([1.0, -1.0, -1.0, 1.0]) @ T_base_tool\n",
        points=0,
        mistake="about x",
    ),
    Variant(
        "0.2",
        "a half turn about y",
        "def base_link_pose(T_base_tool):\n"
        "    return np.diag([-1.0, 1.0, -1.0, 1.0]) @ T_base_tool\n",
        points=0,
        mistake="about y",
    ),
    Variant(
        "0.2",
        "only the position turned",
        "def base_link_pose(T_base_tool):\n"
        "    T = np.array(T_base_tool, dtype=float)\n"
        "    T[:2, 3] *= -1\n"
        "    return T\n",
        points=0,
        mistake="only the position",
    ),
    Variant(
        "0.2",
        "only the orientation turned",
        "def base_link_pose(T_base_tool):\n"
        "    T = np.array(T_base_tool, dtype=float)\n"
        "    T[:3, :3] = np.diag([-1.0, -1.0, 1.0]) @ T[:3, :3]\n"
        "    return T\n",
        points=0,
        mistake="only the orientation",
    ),
    Variant(
        "0.2",
        "the inverse of T",
        "def base_link_pose(T_base_tool):\n"
        "    return np.diag([-1.0, -1.0, 1.0, 1.0]) @ np.linalg.inv(T_base_tool)\n",
        points=0,
        mistake="inverse",
    ),
    Variant(
        "0.2",
        "urkin's T_BASE_LINK_BASE (forbidden)",
        "def base_link_pose(T_base_tool):\n    return urkin.T_BASE_LINK_BASE @ T_base_tool\n",
        points=0,
    ),
    Variant(
        "0.2",
        "urkin.robots.T_BASE_LINK_BASE imported inside (forbidden)",
        "def base_link_pose(T_base_tool):\n"
        "    from urkin.robots import T_BASE_LINK_BASE\n"
        "    return T_BASE_LINK_BASE @ T_base_tool\n",
        points=0,
    ),
    Variant(
        "0.2",
        "the 3×3 rotation only",
        "def base_link_pose(T_base_tool):\n"
        "    return np.diag([-1.0, -1.0, 1.0]) @ T_base_tool[:3, :3]\n",
        points=0,
    ),
    Variant(
        "0.2", "a constant", "def base_link_pose(T_base_tool):\n    return np.eye(4)\n", points=0
    ),
    # ---------------------------------------------------------------- 0.3 turn_joint1
    Variant(
        "0.3",
        "right-multiplied: about the flange's own z axis",
        "def turn_joint1(T_base_flange, angle):\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    Rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return T_base_flange @ Rz\n",
        points=0,
        mistake="wrong side",
    ),
    Variant(
        "0.3",
        "the opposite angle (Rz transposed)",
        "def turn_joint1(T_base_flange, angle):\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    Rz = np.array([[c, s, 0, 0], [-s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return Rz @ T_base_flange\n",
        points=0,
        mistake="−angle",
    ),
    Variant(
        "0.3",
        "only the orientation turned",
        "def turn_joint1(T_base_flange, angle):\n"
        "    T = np.array(T_base_flange, dtype=float)\n"
        "    T[:3, :3] = urkin.transforms.rot_z(angle) @ T[:3, :3]\n"
        "    return T\n",
        points=0,
        mistake="only the orientation",
    ),
    Variant(
        "0.3",
        "only the position turned",
        "def turn_joint1(T_base_flange, angle):\n"
        "    T = np.array(T_base_flange, dtype=float)\n"
        "    T[:3, 3] = urkin.transforms.rot_z(angle) @ T[:3, 3]\n"
        "    return T\n",
        points=1,
        mistake="only the position",
    ),
    Variant(
        "0.3",
        "the angle taken as degrees",
        "def turn_joint1(T_base_flange, angle):\n"
        "    a = np.radians(angle)\n"
        "    c, s = np.cos(a), np.sin(a)\n"
        "    Rz = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
        "    return Rz @ T_base_flange\n",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "0.3",
        "a turn about x",
        "def turn_joint1(T_base_flange, angle):\n"
        "    turn = urkin.transforms.make_transform(urkin.transforms.rot_x(angle))\n"
        "    return turn @ T_base_flange\n",
        points=0,
        mistake="about the base's x axis",
    ),
    Variant(
        "0.3",
        "unchanged",
        "def turn_joint1(T_base_flange, angle):\n    return T_base_flange\n",
        points=0,
        mistake="unchanged",
    ),
    Variant(
        "0.3",
        "the 3×3 rotation only",
        "def turn_joint1(T_base_flange, angle):\n"
        "    return urkin.transforms.rot_z(angle) @ T_base_flange[:3, :3]\n",
        points=0,
    ),
    Variant(
        "0.3",
        "a constant",
        "def turn_joint1(T_base_flange, angle):\n    return np.eye(4)\n",
        points=0,
    ),
]
