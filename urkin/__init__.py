"""urkin: kinematics of Universal Robots arms.

The public API::

    import urkin
    ur5 = urkin.robot("ur5")          # a Robot; urkin.ROBOTS lists the names
    T = urkin.fk(ur5, q)              # (4, 4) for q (6,); (N, 4, 4) for q (N, 6)
    Ts = urkin.fk_frames(ur5, q)      # (7, 4, 4): the base, then DH frames 1 … 6
    J = urkin.jacobian(ur5, q)        # (6, 6): [v; ω] of the tool origin, base frame
    Jp = urkin.position_jacobian(ur5, q)  # (3, 6): ∂p/∂q
    S, M = urkin.poe.space_screws(ur5)    # screw axes (6, 6) and home pose (product of exps)
    res = urkin.ik(ur5, T, q0=q0)         # IKResult(q, success, residual, iterations, ...)
    sols = urkin.ik_analytic(ur5, T)      # (k, 6), k ≤ 8: every exact closed-form solution

Units are metres and radians; poses are 4×4 homogeneous transforms in DH frame 0 (UR's
``base``).  ``import urkin`` loads numpy only: SymPy stays in :mod:`urkin.symbolic` and
matplotlib in :mod:`urkin.plot`.  The course built on the library (lessons, checks, the
autograder) is the separate wing :mod:`urkin.course`; the library never imports it.
"""

from urkin import kinematics, poe, robots, transforms
from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.kinematics import fk, fk_frames, jacobian, position_jacobian
from urkin.numerical_ik import IKResult, ik
from urkin.robots import ROBOTS, T_BASE_LINK_BASE, Robot, robot

__all__ = [
    "ROBOTS",
    "T_BASE_LINK_BASE",
    "IKResult",
    "Robot",
    "fk",
    "fk_frames",
    "ik",
    "ik_analytic",
    "ik_closest",
    "jacobian",
    "kinematics",
    "poe",
    "position_jacobian",
    "robot",
    "robots",
    "transforms",
]

__version__ = "0.1.0"
