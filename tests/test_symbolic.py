import subprocess
import sys

import numpy as np
import sympy as sp

import urkin
from tests.reference import OFFICIAL_DH, dh_fk
from urkin import symbolic


def test_generated_code_is_what_the_derivation_writes():
    committed = symbolic.GENERATED_PATH.read_text(encoding="utf-8")
    assert committed == symbolic.generate_code(), (
        "urkin/_generated/ur_kinematics.py is out of date: run `python -m urkin.symbolic`"
    )


def test_symbolic_t06_evaluates_to_the_dh_product(rng):
    T = symbolic.ur_t06()
    for name in ("UR3", "UR10e"):
        q = rng.uniform(-np.pi, np.pi, 6)
        values = dict(zip(symbolic.Q, q)) | dict(zip(symbolic.LENGTHS, OFFICIAL_DH[name]))
        np.testing.assert_allclose(
            np.array(T.evalf(subs=values), dtype=float), dh_fk(OFFICIAL_DH[name], q), atol=1e-12
        )


def test_position_jacobian_is_the_linear_part_of_the_geometric_jacobian():
    difference = symbolic.ur_geometric_jacobian()[:3, :] - symbolic.ur_position_jacobian()
    assert difference.applyfunc(sp.simplify) == sp.zeros(3, 6)


def test_modified_and_standard_conventions_differ():
    t, d, a, al = sp.symbols("theta d a alpha")
    standard = symbolic.dh_transform(t, d, a, al)
    modified = symbolic.dh_transform(t, d, a, al, convention="modified")
    assert sp.simplify(standard - modified) != sp.zeros(4, 4)
    # modified is Rx(α) Tx(a) Rz(θ) Tz(d): its translation has no θ
    assert t not in modified[:3, 3].free_symbols


def test_lambdified_symbolic_fk_matches_urkin(rng):
    f = sp.lambdify((symbolic.Q, symbolic.LENGTHS), symbolic.ur_t06(), "numpy")
    ur5 = urkin.robot("ur5")
    q = rng.uniform(-np.pi, np.pi, 6)
    np.testing.assert_allclose(f(q, ur5.lengths), urkin.fk(ur5, q), atol=1e-14)


def test_import_urkin_does_not_load_sympy_or_matplotlib():
    code = (
        "import sys, urkin; "
        "bad = [m for m in ('sympy', 'matplotlib') if m in sys.modules]; "
        "print(','.join(bad))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
