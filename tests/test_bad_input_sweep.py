"""Every public function, fed garbage in each argument in turn: it must refuse it with a
TypeError or ValueError whose message is urkin's (not numpy's "could not broadcast" or
Python's "has no attribute"), or accept it only where accepting it is documented.

The garbage: None, a string, a bool, NaN, infinity, complex numbers, one entry too many, an
empty stack, strings in an array, a ragged list, a (2, 3)-grid stack, entries of 1e300, float32
and object arrays; and for every numeric
keyword option: NaN, −1, 0, infinity, a string, 1e300."""

from __future__ import annotations

import inspect
import warnings

import numpy as np
import pytest

import urkin
from urkin import kinematics as km
from urkin import planning as pl
from urkin import poe
from urkin import trajectory as tj
from urkin import transforms as tf

UR5 = urkin.robot("ur5")
Q = np.array([0.1, -1.2, 1.1, -0.5, 0.7, 0.3])
T = urkin.fk(UR5, Q)
R = T[:3, :3]
S0, M0 = poe.space_screws(UR5)
B0, _ = poe.body_screws(UR5)
TWIST = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
MODEL = pl.sphere_model(UR5)
SCENE = pl.Scene(boxes=[pl.Box([0.5, 0, 0.2], [0.1, 0.1, 0.1])])
QA = np.array([0, -1.57, 0, -1.57, 0, 0.0])
QB = QA + 0.3
J = urkin.jacobian(UR5, Q)

CALLS = {
    "transforms.adjoint": (tf.adjoint, [T]),
    "transforms.check_rotation": (tf.check_rotation, [R]),
    "transforms.check_transform": (tf.check_transform, [T]),
    "transforms.inv_transform": (tf.inv_transform, [T]),
    "transforms.make_transform": (tf.make_transform, [R, [1, 2, 3]]),
    "transforms.orthonormalize": (tf.orthonormalize, [R]),
    "transforms.pose_error": (tf.pose_error, [T, T]),
    "transforms.rot_x": (tf.rot_x, [0.3]),
    "transforms.rotation_angle": (tf.rotation_angle, [R]),
    "transforms.rotation_parts": (tf.rotation_parts, [R]),
    "transforms.rotation_to_rpy": (tf.rotation_to_rpy, [R]),
    "transforms.rpy_to_rotation": (tf.rpy_to_rotation, [[0.1, 0.2, 0.3]]),
    "transforms.se3_exp": (tf.se3_exp, [TWIST]),
    "transforms.se3_log": (tf.se3_log, [T]),
    "transforms.skew": (tf.skew, [[1, 2, 3]]),
    "transforms.so3_exp": (tf.so3_exp, [[0.1, 0.2, 0.3]]),
    "transforms.so3_log": (tf.so3_log, [R]),
    "transforms.twist_matrix": (tf.twist_matrix, [TWIST]),
    "transforms.twist_vector": (tf.twist_vector, [tf.twist_matrix(TWIST)]),
    "transforms.unskew": (tf.unskew, [tf.skew([1, 2, 3])]),
    "transforms.wrap_angles": (tf.wrap_angles, [Q]),
    "transforms.random_rotations": (tf.random_rotations, [3, 0]),
    "transforms.random_transforms": (tf.random_transforms, [3, 0]),
    "fk": (urkin.fk, [UR5, Q]),
    "fk_frames": (urkin.fk_frames, [UR5, Q]),
    "jacobian": (urkin.jacobian, [UR5, Q]),
    "position_jacobian": (urkin.position_jacobian, [UR5, Q]),
    "ik": (urkin.ik, [UR5, T]),
    "ik_analytic": (urkin.ik_analytic, [UR5, T]),
    "ik_closest": (urkin.ik_closest, [UR5, T, Q]),
    "robot": (urkin.robot, ["ur5"]),
    "Robot.with_base": (UR5.with_base, [T]),
    "Robot.with_tool": (UR5.with_tool, [T]),
    "kinematics.check_joints": (km.check_joints, [Q]),
    "kinematics.condition_number": (km.condition_number, [UR5, Q]),
    "kinematics.dh_chain": (km.dh_chain, [UR5.dh_table(), Q]),
    "kinematics.dh_transform": (km.dh_transform, [0.1, 0.2, 0.3, 0.4]),
    "kinematics.manipulability": (km.manipulability, [UR5, Q]),
    "kinematics.singularities": (km.singularities, [UR5, Q]),
    "kinematics.singularity_factors": (km.singularity_factors, [UR5, Q]),
    "kinematics.singular_families": (km.singular_families, [UR5, Q]),
    "kinematics.flange_pose": (km.flange_pose, [UR5, T]),
    "poe.space_screws": (poe.space_screws, [UR5]),
    "poe.body_screws": (poe.body_screws, [UR5]),
    "poe.fk_space": (poe.fk_space, [M0, S0, Q]),
    "poe.fk_body": (poe.fk_body, [M0, B0, Q]),
    "poe.jacobian_space": (poe.jacobian_space, [S0, Q]),
    "poe.jacobian_body": (poe.jacobian_body, [B0, Q]),
    "poe.screw_axis": (poe.screw_axis, [[0, 0, 1], [0.1, 0, 0]]),
    "poe.geometric_from_space": (poe.geometric_from_space, [J, T]),
    "poe.space_from_geometric": (poe.space_from_geometric, [J, T]),
    "trajectory.line": (tj.line, [[0, 0, 0], [0.1, 0, 0]]),
    "trajectory.circle": (tj.circle, [[0.4, 0, 0.3], 0.05, "xy"]),
    "trajectory.square": (tj.square, [[0.4, 0, 0.3], 0.1, "xy"]),
    "trajectory.polyline": (tj.polyline, [[[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0]]]),
    "trajectory.time_scaling": (tj.time_scaling, ["quintic", 2.0]),
    "trajectory.minimum_time": (tj.minimum_time, ["quintic", [1.0, 0.5], [1.0, 1.0], [2.0, 2.0]]),
    "trajectory.joint_trajectory": (
        tj.joint_trajectory,
        [QA, QB, tj.time_scaling("quintic", 2.0)],
    ),
    "trajectory.via_trajectory": (tj.via_trajectory, [np.array([QA, QB, QA]), [0.0, 1.0, 2.0]]),
    "trajectory.pose_path": (tj.pose_path, [tj.line([0.4, 0, 0.3], [0.5, 0, 0.3]), R, R]),
    "trajectory.track": (tj.track, [UR5, urkin.fk(UR5, np.array([Q, Q + 0.01])), Q]),
    "planning.is_free": (pl.is_free, [MODEL, SCENE, Q]),
    "planning.clearance": (pl.clearance, [MODEL, SCENE, Q]),
    "planning.explain": (pl.explain, [MODEL, SCENE, Q]),
    "planning.edges_free": (pl.edges_free, [MODEL, SCENE, QA, QB]),
    "planning.certify_edges": (pl.certify_edges, [MODEL, SCENE, QA, QB]),
    "planning.edge_samples": (pl.edge_samples, [MODEL, QA, QB]),
    "planning.rrt_connect": (pl.rrt_connect, [MODEL, SCENE, QA, QB]),
    "planning.shortcut": (pl.shortcut, [MODEL, SCENE, np.array([QA, QB])]),
    "planning.self_pairs": (pl.self_pairs, [MODEL]),
    "planning.Box": (pl.Box, [[0, 0, 0], [0.1, 0.1, 0.1]]),
    "planning.Cylinder": (pl.Cylinder, [[0, 0, 0], [0, 0, 1], 0.1, 0.2]),
    "planning.Sphere": (pl.Sphere, [[0, 0, 0], 0.1]),
    "planning.Capsule": (pl.Capsule, [[0, 0, 0], [0, 0, 1], 0.1]),
    "planning.box_separation": (
        pl.box_separation,
        [[0, 0, 0], np.eye(3), [0.1, 0.1, 0.1], [1, 0, 0], np.eye(3), [0.1, 0.1, 0.1]],
    ),
    "planning.tool_yaw": (pl.tool_yaw, [T]),
    "planning.block_spheres": (pl.block_spheres, [[0.05, 0.05, 0.04]]),
    "planning.top_down_grasp": (
        pl.top_down_grasp,
        [pl.Block.standing("A", [0.05, 0.05, 0.04], x=0.3, y=0.1)],
    ),
    "SphereModel.place": (MODEL.place, [Q]),
    "SphereModel.with_tool_spheres": (MODEL.with_tool_spheres, [[[0, 0, 0.05]], [0.03]]),
}

#: Garbage some functions take on purpose, as their docstrings say: complex angles for the
#: complex step; None for "the default" (identity, no rotation change, a fresh seed).
DOCUMENTED = {
    ("fk", 1, "complex"),
    ("fk_frames", 1, "complex"),
    ("jacobian", 1, "complex"),
    ("position_jacobian", 1, "complex"),
    ("SphereModel.place", 0, "complex"),  # placed by fk_frames, complex step and all
    ("transforms.make_transform", 0, "None"),
    ("transforms.make_transform", 1, "None"),
    ("transforms.wrap_angles", 0, "nan"),  # NaN stays NaN: rows that are not solutions
    ("trajectory.pose_path", 1, "None"),
    ("trajectory.pose_path", 2, "None"),
    ("Robot.with_base", 0, "None"),
    ("Robot.with_tool", 0, "None"),
    ("transforms.random_rotations", 1, "None"),
    ("transforms.random_transforms", 1, "None"),
    ("transforms.random_rotations", 1, "ragged"),  # numpy seeds with any nested integers
    ("transforms.random_transforms", 1, "ragged"),
}

#: Words of Python's and numpy's own errors: an error that says only these leaves the user
#: to guess which argument was wrong.
FOREIGN = (
    "could not be broadcast",
    "setting an array element",
    "could not convert",
    "object of type",
    "unsupported operand",
    "not subscriptable",
    "has no attribute",
    "inhomogeneous",
    "truth value",
    "did not contain a loop",
    "not supported between",
)

OPAQUE = (urkin.Robot, pl.SphereModel, pl.Scene, pl.Plan, tj.TimeScaling, tj.Path, str)


def garbage(value) -> list[tuple[str, object]]:
    out = [("None", None), ("str", "abc"), ("bool", True)]
    if isinstance(value, OPAQUE):
        return [*out, ("float", 1.0), ("array", np.zeros(6))]
    a = np.asarray(value)
    if a.dtype.kind not in "fiu":
        return out
    for label, entry in (("nan", np.nan), ("inf", np.inf)):
        x = a.astype(float).copy()
        x.flat[0] = entry
        out.append((label, x))
    out.append(("complex", a.astype(complex) + 1e-3j))
    out.append(("one more", np.zeros((*a.shape[:-1], a.shape[-1] + 1)) if a.ndim else [0, 0]))
    out.append(("strings", np.full(a.shape or (1,), "x").tolist()))
    out.append(("ragged", [[1, 2], [3]]))
    out.append(("grid", np.broadcast_to(a, (2, 3, *a.shape)).copy()))
    out.append(("empty stack", np.zeros((0, *a.shape))))
    out.append(("huge", np.full(a.shape, 1e300)))  # norms and products overflow
    out.append(("float32", a.astype(np.float32)))
    out.append(("objects", a.astype(object)))
    return out


def outcome(call) -> str:
    """'' if ``call`` returns, else what is wrong with the error it raised ('' for a good one)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            call()
    except (TypeError, ValueError) as error:
        message = str(error)
        if len(message) < 15 or any(words in message for words in FOREIGN):
            return f"unclear {type(error).__name__}: {message[:100]}"
        return "refused"
    except Exception as error:  # any other kind is the finding
        return f"{type(error).__name__}: {str(error)[:100]}"
    return ""


@pytest.mark.parametrize("name", sorted(CALLS))
def test_garbage_in_every_argument_is_refused_by_name(name):
    function, arguments = CALLS[name]
    function(*arguments)  # the template itself is fine
    problems = []
    for k, value in enumerate(arguments):
        for label, bad in garbage(value):
            changed = [*arguments[:k], bad, *arguments[k + 1 :]]
            result = outcome(lambda changed=changed: function(*changed))
            if result == "refused":
                continue
            if result == "" and (
                label not in ("nan", "inf", "complex", "str", "None", "strings", "ragged")
                or (name, k, label) in DOCUMENTED
            ):
                continue  # taken: a value it may take (an empty stack, a grid, one more entry)
            problems.append(f"argument {k} = {label}: {result or 'accepted silently'}")
    assert not problems, f"{name}:\n" + "\n".join(problems)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_bad_numeric_options_are_refused_by_name(name):
    function, arguments = CALLS[name]
    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):
        return
    problems = []
    for p in parameters:
        default = p.default
        if isinstance(default, bool) or not isinstance(default, (int, float)):
            continue
        for label, bad in (("nan", np.nan), ("−1", -1.0), ("inf", np.inf), ("str", "x")):
            result = outcome(lambda p=p, bad=bad: function(*arguments, **{p.name: bad}))
            if result == "refused" or (result == "" and label in ("−1", "inf")):
                continue
            problems.append(f"{p.name} = {label}: {result or 'accepted silently'}")
    assert not problems, f"{name}:\n" + "\n".join(problems)


def test_pick_and_place_names_moves_that_are_not_a_sequence():
    from urkin.course.tabletop import LAB_HOME, hanoi_world

    world = hanoi_world(2)
    for moves in (float("nan"), None, "D1 0.3 0.1", pl.Move("D1", 0.3, 0.1)):
        with pytest.raises(TypeError, match="moves must be a sequence"):
            pl.pick_and_place(world, moves, LAB_HOME)


def test_drawing_functions_name_bad_arguments():
    """The plotting entry points check their robot, angles, pose and scene like the library."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from urkin import plot

    cases = [
        (lambda: plot.show_robot("ur5", Q), TypeError, "robot must be a urkin Robot"),
        (lambda: plot.show_robot(UR5, [0, 1, "x", 0, 0, 0]), TypeError, "q must be numbers"),
        (lambda: plot.show_robot(UR5, Q + 1e-3j), TypeError, "q is complex"),
        (lambda: plot.show_robot(UR5, np.stack([Q, Q])), ValueError, "one configuration"),
        (lambda: plot.pose_text(np.stack([T, T])), ValueError, "pose_text shows one pose"),
        (lambda: plot.animate_plan(UR5, np.stack([Q, Q]), None), TypeError, "scene must be a"),
        (lambda: plot.animate_plan(UR5, "abc", SCENE), TypeError, "qs must be numbers"),
    ]
    try:
        for call, error, message in cases:
            with pytest.raises(error, match=message):
                call()
    finally:
        plt.close("all")


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (  # stacks that do not broadcast: urkin's message, not numpy's
            lambda: urkin.numerical_ik.orientation_error(
                tf.random_rotations(2, 0), tf.random_rotations(3, 1)
            ),
            ValueError,
            "R_current and R_target must be rotations of matching stacks",
        ),
        # check=False is for float arrays of poses; anything else is checked anyway
        (lambda: tf.pose_error(np.eye(3), np.eye(3), check=False), ValueError, "T1 must have"),
        (lambda: tf.pose_error(T, [[1, 2]], check=False), ValueError, "T2 must have"),
        (lambda: tf.wrap_angles(["a"], check=False), TypeError, "q must be numbers"),
        # a ragged list: its rows have different lengths (not "must be numbers")
        (lambda: urkin.fk(UR5, [[0] * 6, [0] * 5]), ValueError, "q must be a regular array"),
        (lambda: tf.so3_exp([[1, 2, 3], [1, 2]]), ValueError, "rows have different lengths"),
        # DH lengths: any real number but a bool, by name
        (lambda: urkin.Robot("arm", True, -0.4, -0.4, 0.1, 0.1, 0.1), TypeError, "d1 must be a"),
        (lambda: urkin.Robot("arm", 0.1, "x", -0.4, 0.1, 0.1, 0.1), TypeError, "a2 must be a"),
        (lambda: urkin.Robot("arm", 0.1, -0.4, np.nan, 0.1, 0.1, 0.1), ValueError, "a3 must be"),
        # a scalar home pose or screw list reports its own shape, ()
        (lambda: poe.fk_space(1.0, S0, Q), ValueError, "M must have shape (4, 4); got ()"),
        (lambda: poe.fk_space(M0, 1.0, Q), ValueError, "got ()"),
        (lambda: poe.space_screws(np.zeros((0, 3))), ValueError, "at least one"),
        (lambda: urkin.ik_closest(UR5, T, np.zeros(5)), ValueError, "shape (6,) for T"),
        (
            lambda: tj.line((-1e308, 0, 0), (1e308, 0, 0)),
            ValueError,
            "points 0 and 1 are too far apart",
        ),
    ],
)
def test_audited_inputs_get_errors_that_name_them(call, error, message):
    with pytest.raises(error) as raised:
        call()
    assert message in str(raised.value)


def test_numeric_scalars_are_lengths_and_far_targets_warn_nothing():
    arm = urkin.Robot("arm", np.float32(0.1), np.int64(0), -0.4, 0.1, 0.1, 0.1)
    assert all(type(x) is float for x in (arm.d1, arm.a2)) and arm.d1 == float(np.float32(0.1))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning on the way to the reason
        result = urkin.ik(UR5, [1e300, 0.0, 0.0])
    assert not result.success and "1e+300 m beyond the UR5's reach" in result.reason
