"""Reading a submission's SymPy answer from its srepr text, without running the text."""

import numpy as np
import pytest

from urkin.course import symbolic_answer, wire

sp = pytest.importorskip("sympy")


def _random_values(names, rng, n=50):
    return {name: rng.uniform(-3, 3, n) for name in names}


@pytest.mark.parametrize(
    "expression",
    [
        "2*x + cos(y)",
        "sin(x)**2 + cos(x)**2 - 1",
        "Rational(3, 7)*x - sqrt(2)*y/5 + pi",
        "atan2(y, x) + exp(-x**2) + Abs(y)*sign(x)",
        "0.1524*cos(x) - 0.0853*sin(x + y)",
        "log(x**2 + 1) + tan(x/7) + asin(y/4) + acos(x/4) + atan(y)",
        "E**x - 1/(x**2 + y**2 + 1)",
    ],
)
def test_expressions_evaluate_as_sympy_does(expression):
    x, y = sp.symbols("x y")
    expr = sp.sympify(expression, locals={"x": x, "y": y})
    answer = symbolic_answer.read(sp.srepr(expr))
    assert answer.shape == ()
    assert answer.symbols <= {"x", "y"}
    values = _random_values(("x", "y"), np.random.default_rng(1))
    reference = sp.lambdify((x, y), expr, "numpy")(values["x"], values["y"])
    got = answer.evaluate(values)
    np.testing.assert_allclose(got, np.broadcast_to(reference, got.shape), rtol=1e-12, atol=1e-12)


def test_a_matrix_keeps_its_shape_and_its_floats():
    q1, q2 = sp.symbols("q1 q2")
    M = sp.Matrix([[sp.cos(q1), -sp.sin(q1), 0.5], [sp.sin(q2), sp.cos(q2), sp.cos(np.pi / 2)]])
    answer = symbolic_answer.read(sp.srepr(M))
    assert answer.shape == (2, 3)
    assert answer.symbols == {"q1", "q2"}
    assert any(abs(f) < 1e-15 and f != 0 for f in answer.floats)  # cos(π/2) in floating point
    values = _random_values(("q1", "q2"), np.random.default_rng(2), 7)
    got = answer.evaluate(values)
    assert got.shape == (2, 3, 7)
    reference = sp.lambdify((q1, q2), M, "numpy")
    for k in range(7):
        expected = np.array(reference(values["q1"][k], values["q2"][k]), dtype=float)
        np.testing.assert_allclose(got[..., k], expected, atol=1e-15)


def test_a_missing_value_is_named():
    answer = symbolic_answer.read("Add(Symbol('a'), Symbol('b'))")
    with pytest.raises(KeyError, match="b"):
        answer.evaluate({"a": 1.0})


def test_a_negative_base_to_a_fractional_power_is_complex_as_in_sympy():
    x = sp.Symbol("x")
    answer = symbolic_answer.read(sp.srepr(x ** sp.Rational(1, 3)))
    got = answer.evaluate({"x": -8.0})
    assert np.iscomplexobj(got)
    assert abs(got - complex(sp.N((-8) ** sp.Rational(1, 3)))) < 1e-12


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('true')",
        "Symbol('x').__class__",
        "open('/etc/passwd')",
        "eval('1')",
        "(lambda: 1)()",
        "[Symbol('x') for _ in range(10)]",
        "Symbol('x') + 1",  # operators are not srepr: only constructors
        "Symbol('x', commutative=__import__('os'))",
        "Integer(" + "9" * 400 + ")",
        "Matrix([[Integer(1)], [Integer(1), Integer(2)]])",
        "Matrix([])",
        "Rational(1, 0)",
        "Float(Symbol('x'))",
        "Function('f')(Symbol('x'))",
        "Add()",
        "x",
        "Add(" * 5000 + "Integer(1)" + ")" * 5000,
        "not python (",
    ],
)
def test_anything_but_an_expression_is_refused(text):
    with pytest.raises(ValueError):
        symbolic_answer.read(text)


def test_text_too_long_or_not_text_is_refused():
    with pytest.raises(ValueError, match="too long"):
        symbolic_answer.read("Integer(1)" + " " * symbolic_answer.MAX_TEXT)
    with pytest.raises(ValueError, match="too long or not text"):
        symbolic_answer.read(b"Integer(1)")  # type: ignore[arg-type]


def test_a_sympy_answer_crosses_the_wire_as_text_and_comes_back_readable():
    q = sp.symbols("q1:3")
    M = sp.Matrix([[sp.cos(q[0] + q[1]), 0], [0, 1]])
    data = wire.encode(M, lenient=True)
    assert set(data) == {"$sym"}
    back = wire.decode(wire.loads(wire.dumps(data)))
    assert isinstance(back, symbolic_answer.Symbolic)
    assert back.shape == (2, 2)
    np.testing.assert_allclose(back.evaluate({"q1": 0.3, "q2": 0.4})[0, 0], np.cos(0.7))


def test_a_numeric_sympy_matrix_still_crosses_as_an_array():
    data = wire.encode(sp.Matrix([[1, 2], [3, sp.Rational(1, 2)]]), lenient=True)
    np.testing.assert_array_equal(wire.decode(data), [[1.0, 2.0], [3.0, 0.5]])


def test_unreadable_symbolic_text_becomes_an_opaque_answer_not_an_error():
    back = wire.decode({"$sym": "__import__('os')"})
    assert isinstance(back, wire.Opaque)
    assert "unreadable" in back.text


def test_the_sender_and_the_reader_agree_on_the_longest_text():
    assert wire.MAX_SYMBOLIC_TEXT == symbolic_answer.MAX_TEXT
