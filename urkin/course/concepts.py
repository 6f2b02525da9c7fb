"""The library concepts that exercises ask students to write, as urkin implements them.

An exercise names its answer by concept (:attr:`urkin.course.Exercise.answer`); the grader hides
the concept's functions and every library function that uses them
(:mod:`urkin.course.answers`).  Entries are library objects, or dotted names for constants and
for modules a lesson module should not import (SymPy's derivation).  Renaming a function here
fails at import, not silently.
"""

from urkin import analytic_ik, kinematics, numerical_ik, poe, transforms
from urkin.course import lab

__all__ = [
    "BASE_LINK_FRAME",
    "DH_LINK",
    "ELEMENTARY_ROTATIONS",
    "FORWARD_KINEMATICS",
    "INVERSE_KINEMATICS",
    "JACOBIAN",
    "LAB_IK",
    "RIGID_INVERSE",
    "ROTATION_LOG",
    "RPY",
    "SCREW_AXIS",
    "SINGULARITIES",
    "SO3_EXP",
    "TWIST_EXP",
    "TWIST_LOG",
]

#: UR's base frame seen from the URDF base_link frame (Rz(π)).
BASE_LINK_FRAME = ("urkin.robots.T_BASE_LINK_BASE",)
#: Rotations about the coordinate axes (and what gives one in passing: the exponentials, a DH
#: link with d = a = α = 0).
ELEMENTARY_ROTATIONS = (
    transforms.rot_x,
    transforms.rot_y,
    transforms.rot_z,
    transforms.so3_exp,
    transforms.se3_exp,
    transforms.rpy_to_rotation,
    kinematics.dh_transform,
)
#: The inverse of a rigid-body transform (and the exponential/log pair that also gives it).
RIGID_INVERSE = (transforms.inv_transform, transforms.se3_exp, transforms.se3_log)
#: Roll, pitch and yaw of a rotation.
RPY = (transforms.rotation_to_rpy,)
#: Rodrigues' formula, the exponential of so(3) (and of se(3), whose rotation block it is).
SO3_EXP = (transforms.so3_exp, transforms.se3_exp)
#: One standard-DH link transform, numeric and symbolic.
DH_LINK = (kinematics.dh_transform, kinematics.dh_chain, "urkin.symbolic.dh_transform")
#: The flange pose of a UR arm: DH products, the generated code, SymPy's derivation, PoE.
FORWARD_KINEMATICS = (
    kinematics.fk,
    kinematics.fk_frames,
    kinematics.dh_chain,
    "urkin._generated.ur_kinematics",
    "urkin.symbolic.ur_frames",
    poe.fk_space,
    poe.fk_body,
    # the closed-form flange position the checks of exercise 2.7 hand out as a candidate
    "urkin.course.wire.ur_flange_position",
)
#: The screw axis of a revolute joint.
SCREW_AXIS = (poe.screw_axis,)
#: The exponential of a twist, e^[S]θ (and the product-of-exponentials machinery).
TWIST_EXP = (transforms.se3_exp, poe)
#: The logarithm of a rigid motion, log T = [V] (and the IK core, whose matrix-log step uses it).
TWIST_LOG = (transforms.se3_log,)
#: The geometric Jacobian and its space and body forms.
JACOBIAN = (
    kinematics.jacobian,
    kinematics.position_jacobian,
    poe.jacobian_space,
    poe.jacobian_body,
    "urkin._generated.ur_kinematics.jacobian_one",
    "urkin._generated.ur_kinematics.jacobian_many",
    "urkin._generated.ur_kinematics.position_jacobian_one",
    "urkin._generated.ur_kinematics.position_jacobian_many",
    "urkin.symbolic.ur_geometric_jacobian",
    "urkin.symbolic.ur_position_jacobian",
)
#: Which singular families hold, and the measures built on the Jacobian's determinant.
SINGULARITIES = (
    kinematics.singularities,
    kinematics.singular_families,
    kinematics.singularity_factors,
    kinematics.manipulability,
    kinematics.condition_number,
)
#: The rotation vector (matrix log) between orientations.
ROTATION_LOG = (
    transforms.so3_log,
    transforms.rotation_parts,
    transforms.se3_log,
    numerical_ik,
)
#: Every inverse kinematics solver: numerical, closed form and the lab's (the numerical solver's
#: step rules go with it: only it uses them).
INVERSE_KINEMATICS = (numerical_ik.ik, analytic_ik.ik_analytic, analytic_ik.ik_closest, lab.ik_lab)
#: The UR3 lab's closed-form IK and the general closed form it is a branch of.
LAB_IK = (lab.ik_lab, analytic_ik.ik_analytic, analytic_ik.ik_closest, numerical_ik.ik)
