"""Lesson 06 — damped least squares and Levenberg–Marquardt."""

from __future__ import annotations

import numpy as np

import urkin
from urkin.exercises.framework import Check, Exercise, Mismatch, as_array, compare, register
from urkin.exercises.inputs import random_arm, random_q, random_regular_q
from urkin.numerical_ik import orientation_error

_fk, _ik = urkin.fk, urkin.ik  # references, bound before any grading guard is installed
_orientation_error = orientation_error

_IK_FUNCTIONS = (
    "urkin.numerical_ik.ik",
    "urkin.numerical_ik._iterate_one",
    "urkin.numerical_ik._iterate_batch",
    "urkin.numerical_ik._damped_step",
)


def _random_jacobian(rng, rows: int, singular: bool = False) -> np.ndarray:
    J = rng.normal(size=(rows, 6))
    if singular:  # make two rows dependent: the arm has lost a direction
        J[1] = 0.5 * J[0]
    return J


def _seed000_elementwise(J, e, lam):
    """Seed 000's crashing line made to run: element-wise * and **-1 where @ and inv belong."""
    return (J.T * (J * J.T + lam**2 * np.eye(J.shape[0])) ** -1) @ e


def _seed001_minus(J, e, mu):
    """Seed 001's printed update, (JᵀJ + μI)⁻¹ − JᵀV, with its minus where a product belongs."""
    return np.linalg.inv(J.T @ J + mu * np.eye(J.shape[1])) - J.T @ e


_SEED000 = (
    "seed 000's first DLS line: in numpy * and **-1 are element-wise; the damped inverse "
    "needs matrix products (@) and a solve"
)
_SEED001 = "seed 001's update (JᵀJ + μI)⁻¹ − JᵀV: the minus should be a product, (JᵀJ + μI)⁻¹ JᵀV"


def _call_step(student, J, e, damping, name: str) -> np.ndarray:
    """The student's step as a (6,) array, or a Mismatch that names the seeds' mistakes."""
    inputs = {"J": J, "e": e, "lam" if name == "dls_step" else "mu": damping}
    try:
        value = student(J.copy(), e.copy(), damping)
    except NameError as exc:
        if "'I'" in str(exc):
            raise Mismatch(
                f"{name} raised NameError: {exc}",
                inputs=inputs,
                mistake=_SEED000 + " (and I is undefined there)",
            ) from None
        raise
    array = np.asarray(value, dtype=float) if value is not None else None
    if array is not None and array.shape == (6, 6):
        mu = damping if name == "lm_step" else damping**2
        if np.allclose(array, _seed001_minus(J, e, mu), atol=1e-9):
            raise Mismatch(
                f"{name} must return the step Δq, shape (6,); got a 6×6 matrix",
                inputs=inputs,
                mistake=_SEED001,
            )
    return as_array(value, (6,), f"{name}(J, e, {'lam' if name == 'dls_step' else 'mu'})")


# ------------------------------------------------------------------------------ 6.1 dls_step


def _dls_expected(J, e, lam):
    return J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(J.shape[0]), e)


def _dls_hypotheses(J, e, lam):
    return {
        _SEED000: lambda: _seed000_elementwise(J, e, lam),
        "λ where λ² belongs: Jᵀ(JJᵀ + λ²I)⁻¹e": lambda: (
            J.T @ np.linalg.solve(J @ J.T + lam * np.eye(J.shape[0]), e)
        ),
        "no damping: that is the plain pseudo-inverse step": lambda: np.linalg.pinv(J) @ e,
    }


def _dls_matches(student, rng):
    for rows in (6, 6, 6, 3, 3):
        J, e, lam = _random_jacobian(rng, rows), rng.normal(size=rows), rng.uniform(0.05, 0.5)
        got = _call_step(student, J, e, lam, "dls_step")
        compare(
            got,
            _dls_expected(J, e, lam),
            what="Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e",
            inputs={"J": J, "e": e, "lam": lam},
            hypotheses=_dls_hypotheses(J, e, lam),
        )


def _dls_at_singularities(student, rng):
    for rows in (6, 3):
        J, e, lam = _random_jacobian(rng, rows, singular=True), rng.normal(size=rows), 0.01
        got = _call_step(student, J, e, lam, "dls_step")
        compare(
            got,
            _dls_expected(J, e, lam),
            atol=1e-6,
            what="with a singular J the damped step stays finite: ‖Δq‖ ≤ ‖e‖ / (2λ)",
            inputs={"J": J, "e": e, "lam": lam},
            hypotheses=_dls_hypotheses(J, e, lam),
        )


register(
    Exercise(
        id="6.1",
        function="dls_step",
        title="the damped least-squares step",
        checks=(
            Check("matches Jᵀ(JJᵀ + λ²I)⁻¹e for 6×6 and 3×6 Jacobians", 2, _dls_matches),
            Check("stays finite and right when J is singular", 1, _dls_at_singularities),
        ),
        forbidden=_IK_FUNCTIONS,
    )
)


# ------------------------------------------------------------------------------- 6.2 lm_step


def _lm_expected(J, e, mu):
    return np.linalg.solve(J.T @ J + mu * np.eye(J.shape[1]), J.T @ e)


def _lm_hypotheses(J, e, mu):
    return {
        "μ² where μ belongs: Levenberg–Marquardt adds μI to JᵀJ": lambda: np.linalg.solve(
            J.T @ J + mu**2 * np.eye(J.shape[1]), J.T @ e
        ),
        "μ added to every entry of JᵀJ instead of its diagonal (μI)": lambda: np.linalg.solve(
            J.T @ J + mu, J.T @ e
        ),
        "the Jᵀ on the right is missing: solve (JᵀJ + μI) Δq = Jᵀe": lambda: np.linalg.solve(
            J.T @ J + mu * np.eye(J.shape[1]), e[: J.shape[1]]
        ),
    }


def _lm_matches(student, rng):
    for rows in (6, 6, 6, 3):
        J, e, mu = _random_jacobian(rng, rows), rng.normal(size=rows), 10 ** rng.uniform(-4, 0)
        got = _call_step(student, J, e, mu, "lm_step")
        compare(
            got,
            _lm_expected(J, e, mu),
            what="Δq = (JᵀJ + μ I)⁻¹ Jᵀ e",
            inputs={"J": J, "e": e, "mu": mu},
            hypotheses=_lm_hypotheses(J, e, mu),
        )


def _lm_is_dls(student, rng):
    # (JᵀJ + μI)⁻¹Jᵀ = Jᵀ(JJᵀ + μI)⁻¹: Levenberg–Marquardt's step is the DLS step with λ² = μ
    for rows in (6, 3):
        J, e, mu = _random_jacobian(rng, rows, singular=True), rng.normal(size=rows), 1e-3
        got = _call_step(student, J, e, mu, "lm_step")
        compare(
            got,
            _dls_expected(J, e, np.sqrt(mu)),
            atol=1e-6,
            what="with λ² = μ the LM step equals the DLS step, singular J included",
            inputs={"J": J, "e": e, "mu": mu},
            hypotheses=_lm_hypotheses(J, e, mu),
        )


register(
    Exercise(
        id="6.2",
        function="lm_step",
        title="the Levenberg–Marquardt step",
        checks=(
            Check("matches (JᵀJ + μI)⁻¹Jᵀe", 2, _lm_matches),
            Check("equals the DLS step with λ² = μ, even at a singularity", 1, _lm_is_dls),
        ),
        forbidden=_IK_FUNCTIONS,
    )
)


# --------------------------------------------------------------------------------- 6.3 ik_lm


def _verify(arm, q, T_target, q0, start: str):
    T = _fk(arm, q)
    position = np.linalg.norm(T[:3, 3] - T_target[:3, 3])
    angle = np.linalg.norm(_orientation_error(T[:3, :3], T_target[:3, :3]))
    if position > 1e-8 or angle > 1e-8:
        raise Mismatch(
            f"from {start}, fk(robot, q) must reach the target within 1e-8 m and 1e-8 rad; "
            f"it misses by {position:.2e} m and {angle:.2e} rad",
            inputs={"robot": arm.name, "q0": q0},
            mistake="a fixed damping, which stops short of targets near singularities (adapt "
            "μ), or a local minimum (restart from a random configuration when μ keeps growing)"
            if 1e-8 < max(position, angle) < 1e-3
            else None,
        )


def _lm_from(student, rng, q0: np.ndarray | None, start: str, count: int):
    """Targets around the start, away from elbow and wrist singularities, that a plain
    Levenberg–Marquardt run (urkin's, without restarts) reaches from that start; without a
    start, the start is 0.5 rad from the target instead."""
    for _ in range(count):
        arm = random_arm(rng)
        while True:
            centre = random_q(rng) if q0 is None else q0
            q_true = random_regular_q(rng, centre, 0.7)
            start_q = q_true + rng.uniform(-0.5, 0.5, 6) if q0 is None else q0.copy()
            T_target = _fk(arm, q_true)
            if _ik(arm, T_target, q0=start_q, max_restarts=0).success:
                break
        q = as_array(student(arm, T_target.copy(), start_q.copy()), (6,), "ik_lm(robot, T, q0)")
        _verify(arm, q, T_target, start_q, start)


def _lm_nearby(student, rng):
    _lm_from(student, rng, None, "a start 0.5 rad away", 5)


def _lm_from_singular_home(student, rng):
    home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
    _lm_from(
        student, rng, home, "the home pose, where shoulder, elbow and wrist are all singular", 4
    )


register(
    Exercise(
        id="6.3",
        function="ik_lm",
        title="Levenberg–Marquardt IK with adaptive damping",
        checks=(
            Check("reaches targets from a start 0.5 rad away", 2, _lm_nearby),
            Check("starts from the triply singular home pose", 2, _lm_from_singular_home),
        ),
        forbidden=_IK_FUNCTIONS,
        builds_on=("6.2",),
    )
)
