"""SymPy derivations of UR kinematics, and the generator of ``urkin/_generated``.

One derivation serves every UR arm: the link lengths ``d1, a2, a3, d4, d5, d6`` stay symbols and
the twists are UR's ``α = (π/2, 0, 0, π/2, −π/2, 0)``.  From the chain of standard-DH transforms
this module derives

* the frames ``T_0_i`` (i = 0 … 6) and the flange pose ``T_0_6``,
* the geometric Jacobian ``[v; ω]`` of the flange origin, column by column from the frames
  (``z_{i-1} × (p − p_{i-1})`` and ``z_{i-1}``),
* the position Jacobian ``∂p/∂q`` by differentiating ``p``,

each simplified into sums of angles (``cos(q2 + q3 + q4)`` and so on), and prints them as plain
numpy code with common-subexpression elimination.  The generated module is committed; run
``python -m urkin.symbolic`` (or ``urkin codegen``) to rewrite it, and the test suite fails when
the committed file differs from what this module would write.

This is the only module of urkin that imports SymPy; ``import urkin`` never loads it.
"""

from __future__ import annotations

import argparse
import functools
import itertools
import sys
from pathlib import Path

import sympy as sp
from sympy.simplify.fu import TR10i

__all__ = [
    "ALPHA_UR",
    "LENGTHS",
    "Q",
    "dh_transform",
    "generate_code",
    "simplify_angles",
    "ur_frames",
    "ur_geometric_jacobian",
    "ur_position_jacobian",
    "ur_t06",
    "write_generated",
]

#: Joint angles q1 … q6 (real symbols).
Q: tuple[sp.Symbol, ...] = sp.symbols("q1:7", real=True)
#: Link lengths d1, a2, a3, d4, d5, d6 (real symbols).
LENGTHS: tuple[sp.Symbol, ...] = sp.symbols("d1 a2 a3 d4 d5 d6", real=True)
#: UR link twists, exact.
ALPHA_UR: tuple[sp.Expr, ...] = (sp.pi / 2, sp.S.Zero, sp.S.Zero, sp.pi / 2, -sp.pi / 2, sp.S.Zero)

GENERATED_PATH = Path(__file__).with_name("_generated") / "ur_kinematics.py"


def dh_transform(theta, d, a, alpha, convention: str = "standard") -> sp.Matrix:
    """Symbolic DH link transform ``T_{i-1,i}``.

    Parameters
    ----------
    theta, d, a, alpha : sympy expressions or numbers
        Joint angle, offset, length and twist of link ``i``.  In the modified convention ``a``
        and ``alpha`` are those of the previous link, ``a_{i-1}`` and ``α_{i-1}``.
    convention : {"standard", "modified"}
        ``"standard"`` (Denavit–Hartenberg): ``Rz(θ) Tz(d) Tx(a) Rx(α)``.
        ``"modified"`` (Craig): ``Rx(α) Tx(a) Rz(θ) Tz(d)``.

    Returns
    -------
    sympy.Matrix, shape (4, 4)

    Examples
    --------
    >>> t, d = sp.symbols("theta d")
    >>> dh_transform(t, d, 0, 0)[:3, 3].T
    Matrix([[0, 0, d]])
    """
    ct, st = sp.cos(theta), sp.sin(theta)
    ca, sa = sp.cos(alpha), sp.sin(alpha)
    if convention == "standard":
        return sp.Matrix(
            [
                [ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0, sa, ca, d],
                [0, 0, 0, 1],
            ]
        )
    if convention == "modified":
        return sp.Matrix(
            [
                [ct, -st, 0, a],
                [st * ca, ct * ca, -sa, -sa * d],
                [st * sa, ct * sa, ca, ca * d],
                [0, 0, 0, 1],
            ]
        )
    raise ValueError(f"convention must be 'standard' or 'modified'; got {convention!r}")


def _sin_squared_to_cos(expr: sp.Expr) -> sp.Expr:
    return expr.replace(
        lambda e: e.is_Pow and e.exp == 2 and isinstance(e.base, sp.sin),
        lambda e: 1 - sp.cos(e.base.args[0]) ** 2,
    )


def simplify_angles(expr: sp.Expr) -> sp.Expr:
    """Fold products of sines and cosines into sines and cosines of sums of angles.

    Expands the expression, removes ``sin² + cos²`` pairs, then applies the sum-of-angles
    identities (``cos a cos b − sin a sin b = cos(a + b)`` and its three siblings, SymPy's
    ``TR10i``) until nothing changes, and pulls common factors out of sums.  On the UR chain
    this gives the same expressions as ``sympy.trigsimp(sympy.expand(expr))`` about thirty times
    faster, because it only tries the identities a serial chain of revolute joints produces.

    Parameters
    ----------
    expr : sympy expression

    Returns
    -------
    sympy expression

    Examples
    --------
    >>> a, b = sp.symbols("a b", real=True)
    >>> simplify_angles(sp.cos(a) * sp.cos(b) - sp.sin(a) * sp.sin(b))
    cos(a + b)
    >>> simplify_angles(sp.sin(a) ** 2 * sp.cos(b) + sp.cos(a) ** 2 * sp.cos(b))
    cos(b)
    """
    expr = sp.expand(_sin_squared_to_cos(sp.expand(expr)))
    previous = None
    while expr != previous:
        previous, expr = expr, TR10i(expr)
    return sp.factor_terms(expr, sign=False)


@functools.cache
def ur_frames() -> tuple[sp.Matrix, ...]:
    """Frames ``T_0_i`` for i = 0 … 6 of the UR chain, simplified into sums of angles.

    Returns
    -------
    tuple of sympy.Matrix
        Seven 4×4 matrices; the first is the identity (the base, DH frame 0).
    """
    d1, a2, a3, d4, d5, d6 = LENGTHS
    table = [(d1, 0), (0, a2), (0, a3), (d4, 0), (d5, 0), (d6, 0)]
    frames = [sp.eye(4)]
    for q, (d, a), alpha in zip(Q, table, ALPHA_UR):
        frames.append((frames[-1] * dh_transform(q, d, a, alpha)).applyfunc(simplify_angles))
    return tuple(frames)


def ur_t06() -> sp.Matrix:
    """Flange pose ``T_0_6(q)`` of a UR arm with symbolic link lengths.

    Examples
    --------
    >>> p = ur_t06()[:3, 3]
    >>> p[2]
    a2*sin(q2) + a3*sin(q2 + q3) + d1 - d5*cos(q2 + q3 + q4) - d6*sin(q5)*sin(q2 + q3 + q4)
    """
    return ur_frames()[-1]


@functools.cache
def ur_geometric_jacobian() -> sp.Matrix:
    """Geometric Jacobian ``[v; ω]`` of the flange origin in the base frame (6×6).

    Column ``i`` is ``[z_{i-1} × (p − p_{i-1}); z_{i-1}]`` with ``z_{i-1}`` and ``p_{i-1}`` the
    z axis and origin of DH frame ``i − 1``.
    """
    frames = ur_frames()
    p = frames[-1][:3, 3]
    columns = []
    for frame in frames[:-1]:
        z, origin = frame[:3, 2], frame[:3, 3]
        columns.append(sp.Matrix.vstack(z.cross(p - origin), z))
    return sp.Matrix.hstack(*columns).applyfunc(simplify_angles)


@functools.cache
def ur_position_jacobian() -> sp.Matrix:
    """Position Jacobian ``∂p/∂q`` (3×6), by differentiating the flange position."""
    p = ur_t06()[:3, 3]
    return p.jacobian(sp.Matrix(Q)).applyfunc(simplify_angles)


# --------------------------------------------------------------------------- code generation

_COS_SIN = '''
def _cos_sin(angles, c, s):
    """cos and sin of a block of angles into ``c`` and ``s`` (same shape).

    Real angles go through t = tan(angle / 2): cos = 2 / (1 + t²) − 1, sin = 2t / (1 + t²).
    numpy vectorises its tangent but not its float64 sine and cosine, so one tangent and a few
    products cost about a third of a sine and a cosine; the results are within 2.3e-16 of them.
    Complex angles (complex-step derivatives) take numpy's cos and sin.
    """
    if angles.dtype.kind == "c":
        np.cos(angles, out=c)
        np.sin(angles, out=s)
        return
    np.multiply(angles, 0.5, out=s)
    np.tan(s, out=s)
    np.multiply(s, s, out=c)
    np.add(c, 1.0, out=c)
    np.divide(2.0, c, out=c)
    np.multiply(s, c, out=s)
    np.subtract(c, 1.0, out=c)
'''

_HEADER = '''"""Generated by ``python -m urkin.symbolic`` from the derivation in urkin.symbolic.

Do not edit: change urkin/symbolic.py and regenerate.  ``*_one`` functions take six joint
angles as floats and use the math module (fast for one pose); ``*_many`` functions take an
(N, 6) array and run numpy on whole columns, every operation writing into a row of one
workspace (no temporaries).  Both take the link lengths d1, a2, a3, d4, d5, d6.
"""

from math import cos, sin
from struct import Struct

import numpy as np

# one pose is written straight into a fresh array (cheaper than building it from a tuple),
# by a struct whose pad bytes are the constant zeros
_empty = np.empty
'''


def _trig_symbols(exprs: list[sp.Expr]) -> tuple[dict, list[tuple[str, str]]]:
    """Replace cos/sin of sums of joint angles by symbols ``c23``, ``s234``…"""
    index = {q: str(i + 1) for i, q in enumerate(Q)}
    replacements, preamble = {}, []
    atoms = set()
    for expr in exprs:
        atoms |= expr.atoms(sp.cos, sp.sin)
    for atom in sorted(atoms, key=sp.default_sort_key):
        terms = sp.Add.make_args(atom.args[0])
        if not all(t in index for t in terms):
            raise ValueError(f"cannot print {atom}: its argument is not a sum of joint angles")
        digits = "".join(sorted(index[t] for t in terms))
        name = ("c" if isinstance(atom, sp.cos) else "s") + digits
        replacements[atom] = sp.Symbol(name, real=True)
        preamble.append((name, digits))
    return replacements, sorted(preamble, key=lambda item: (len(item[1]), item[1], item[0]))


def _factor_base_rotation(
    entries: dict[tuple[int, ...], sp.Expr], rotated_rows: tuple[tuple[int, int], ...]
) -> dict[tuple[int, ...], sp.Expr]:
    """Entries rewritten as ``Rz(q1)`` applied to their value at ``q1 = 0``.

    Joint 1 turns the whole arm about the base z axis, so ``T_0_i(q) = Rz(q1) T_0_i(q)|q1=0``
    for every frame after the base, and the Jacobians' vector rows turn the same way.  Each
    pair of rows ``(x, y)`` in ``rotated_rows`` whose entries depend on ``q1`` becomes
    ``(c1 x₀ − s1 y₀, s1 x₀ + c1 y₀)`` with ``x₀, y₀`` free of ``q1``: the code computes the arm
    in its vertical plane once and turns it with four products per column (about a fifth fewer
    operations than the expanded entries).  Every rewritten pair is checked to equal the
    original exactly.
    """
    q1 = Q[0]
    c1, s1 = sp.cos(q1), sp.sin(q1)
    out = dict(entries)
    for kx in entries:
        *lead, row, col = kx
        partner = dict(rotated_rows).get(row)
        if partner is None:
            continue
        ky = (*lead, partner, col)
        ex, ey = entries[kx], entries[ky]
        if q1 not in ex.free_symbols | ey.free_symbols:
            continue  # the base frame itself: constant
        x0, y0 = simplify_angles(ex.subs(q1, 0)), simplify_angles(ey.subs(q1, 0))
        rx, ry = c1 * x0 - s1 * y0, s1 * x0 + c1 * y0
        for rewritten, original in ((rx, ex), (ry, ey)):
            if sp.expand(sp.expand_trig(rewritten - original)) != 0:  # pragma: no cover
                raise AssertionError(f"entry {kx}: not a rotation about z by q1")
        out[kx], out[ky] = rx, ry
    return out


def _scalar_code(exprs: list[sp.Expr]):
    """The shared part of one-pose code for a list of expressions: their cos/sin symbols, the
    common subexpressions and the expressions in terms of them.

    Returns ``(lines, final, trig, temps, sums, used_q)``: the function's opening lines (angle
    sums, cos/sin, temporaries), the reduced expressions, and what the column code needs."""
    replacements, trig = _trig_symbols(exprs)
    exprs = [sp.sympify(e).xreplace(replacements) for e in exprs]
    # constants stay out of the CSE
    varying = [i for i, e in enumerate(exprs) if not e.is_number]
    temps, reduced = sp.cse(
        [exprs[i] for i in varying], symbols=sp.numbered_symbols("x"), optimizations="basic"
    )
    final = list(exprs)
    for i, e in zip(varying, reduced):
        final[i] = e
    sums = sorted({digits for _, digits in trig if len(digits) > 1}, key=lambda s: (len(s), s))
    used_q = sorted({d for _, digits in trig for d in digits if len(digits) == 1})
    angles = {d for _, digits in trig for d in digits}
    symbols = set().union(*(e.free_symbols for _, e in temps), *(e.free_symbols for e in final))
    unpacked_q = [f"q{i}" if str(i) in angles else "_" for i in range(1, 7)]
    unpacked_lengths = [str(x) if x in symbols else "_" for x in LENGTHS]
    lines = [f"    {', '.join(unpacked_q)} = q", f"    {', '.join(unpacked_lengths)} = lengths"]
    for digits in sums:
        head, last = digits[:-1], digits[-1]
        first = f"q{head}" if head in sums else " + ".join("q" + x for x in head)
        lines.append(f"    q{digits} = {first} + q{last}")
    for sym, digits in trig:
        lines.append(f"    {sym} = {'cos' if sym[0] == 'c' else 'sin'}(q{digits})")
    lines += [f"    {t} = {_pycode(e)}" for t, e in temps]
    return lines, final, trig, temps, sums, used_q


def _printed(final: list[sp.Expr], keys: list, shape: tuple[int, ...], prefix=()) -> list[str]:
    """The entries of an array of ``shape`` (keys ``(*prefix, i, j…)``) as code, row by row;
    numbers as floats (struct packs floats faster than ints)."""
    indices = [(*prefix, *k) for k in _all_indices(shape)]
    flat = [_pycode(final[keys.index(k)]) if k in keys else "0.0" for k in indices]
    return [repr(float(text)) if _is_number(text) else text for text in flat]


def _struct_format(flat: list[str]) -> str:
    """The struct format that packs an array's printed entries as doubles and its constant
    zeros as pad bytes (``pack_into`` zero-fills them, and +0.0 is eight zero bytes), so that
    the generated code passes only the entries that vary."""
    runs = []
    for zero, group in itertools.groupby(text == "0.0" for text in flat):
        count = len(list(group))
        runs.append(f"{8 * count}x" if zero else f"{count}d")
    return "".join(runs)


def _packed(flat: list[str]) -> list[str]:
    """The printed entries a struct of :func:`_struct_format` takes: all but the zeros."""
    return [text for text in flat if text != "0.0"]


def _emit(
    name: str,
    doc: str,
    entries: dict[tuple[int, ...], sp.Expr],
    shape: tuple[int, ...],
    rotated_rows: tuple[tuple[int, int], ...] = ((0, 1),),
):
    """Return the source of ``{name}_one`` and ``{name}_many`` for an array of expressions
    (``rotated_rows``: see :func:`_factor_base_rotation`)."""
    entries = _factor_base_rotation(entries, rotated_rows)
    keys = list(entries)
    lines, final, trig, temps, sums, used_q = _scalar_code([entries[k] for k in keys])
    flat = _printed(final, keys, shape)
    one = [
        f"def {name}_one(q, lengths, out=None, at=0):",
        f'    """{doc} (one pose: ``q`` six floats, ``lengths`` the six link lengths; written',
        "    into ``out`` from byte ``at`` if given; ``out=tuple``: the entries as a tuple of",
        '    floats, row by row, for loops on Python floats)."""',
        *lines,
        "    if out is None:",
        f"        out = _empty({shape})",
        "    elif out is tuple:",
        f"        return ({', '.join(flat)})",
        f"    _pack_{name}(out, at, {', '.join(_packed(flat))})",
        "    return out",
    ]
    many = _emit_many(name, doc, final, keys, shape, trig, temps, sums, used_q)
    packer = f'_pack_{name} = Struct("{_struct_format(flat)}").pack_into'
    return packer + "\n\n\n" + "\n".join(one) + "\n\n\n" + "\n".join(many) + "\n"


def _emit_pose_jacobian(pose: dict, jacobian: dict) -> str:
    """Source of ``pose_jacobian_one``: the flange pose and the Jacobian of one configuration
    from one set of cosines, sines and common subexpressions (an iterative IK needs both at
    every trial configuration)."""
    pose = _factor_base_rotation(pose, ((0, 1),))
    jacobian = _factor_base_rotation(jacobian, ((0, 1), (3, 4)))
    keys = [("T", *k) for k in pose] + [("J", *k) for k in jacobian]
    exprs = [*pose.values(), *jacobian.values()]
    lines, final, *_ = _scalar_code(exprs)
    pose_flat = _printed(final, keys, (4, 4), ("T",))
    jacobian_flat = _printed(final, keys, (6, 6), ("J",))
    return (
        "\n".join(
            [
                "def pose_jacobian_one(q, lengths, out):",
                '    """Flange pose T_0_6 and geometric Jacobian [v; ω] of the flange origin for',
                "    one pose (``q`` six floats, ``lengths`` the six link lengths): writes the",
                "    Jacobian into ``out`` (6, 6) and returns the top three rows of the pose (12",
                '    entries, row by row; the last row is 0, 0, 0, 1) as a tuple."""',
                *lines,
                f"    _pack_jacobian(out, 0, {', '.join(_packed(jacobian_flat))})",
                f"    return ({', '.join(pose_flat[:12])})",
            ]
        )
        + "\n"
    )


class _ColumnCode:
    """Three-address numpy code: every operation writes with ``out=`` into a row of one
    workspace ``w`` or into the output, so a block of poses makes no temporary arrays.
    Intermediates keep their row; scratch rows are reused once their value is consumed."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.rows = 0
        self._free: list[str] = []

    def row(self, name: str = "") -> str:
        """A new row of the workspace, bound to a name once (indexing costs a call too)."""
        name = name or f"w{self.rows}"
        self._op(f"{name} = w[{self.rows}]")
        self.rows += 1
        return name

    def _scratch(self) -> str:
        return self._free.pop() if self._free else self.row()

    def _op(self, text: str) -> None:
        self.lines.append(f"    {text}")

    def into(self, expr: sp.Expr, dst: str) -> None:
        """Code that writes ``expr`` (a polynomial in cos/sin symbols, temporaries and link
        lengths) into the array ``dst``."""
        if _is_scalar(expr):  # a number or lengths only (-d4 too): one value for the row
            self._op(f"{dst}[...] = {_pycode(expr)}")
        elif expr.is_Add:
            self._add(expr, dst)
        elif expr.is_Mul or expr.is_Pow or _is_column(expr):
            self._mul(expr, dst)
        else:  # pragma: no cover - the derivation produces polynomials only
            raise ValueError(f"cannot print {expr} as column code")

    def _operand(self, expr: sp.Expr) -> tuple[str, str | None]:
        """A name that holds ``expr``: a column symbol, or a scratch row filled with it (also
        returned, to be released after use)."""
        if _is_column(expr):
            return str(expr), None
        row = self._scratch()
        self.into(expr, row)
        return row, row

    def _add(self, expr: sp.Add, dst: str) -> None:
        terms = [term.as_coeff_Mul() for term in sp.Add.make_args(expr)]
        constant = sum((c * rest for c, rest in terms if _is_scalar(rest)), sp.S.Zero)
        terms = [(c, rest) for c, rest in terms if not _is_scalar(rest)]
        terms.sort(key=lambda term: (bool(term[0] < 0), not _is_column(term[1])))
        (c, rest), others = terms[0], terms[1:]
        if c > 0 and _is_column(abs(c) * rest) and others:
            current = str(rest)  # a + … starts from the column a itself, not a copy of it
        else:
            self.into(abs(c) * rest, dst)
            if c < 0:
                self._op(f"np.negative({dst}, out={dst})")
            current = dst
        for c, rest in others:
            name, row = self._operand(abs(c) * rest)
            self._op(f"np.{'subtract' if c < 0 else 'add'}({current}, {name}, out={dst})")
            current = dst
            if row:
                self._free.append(row)
        if constant != 0:
            self._op(f"np.add({dst}, {_pycode(constant)}, out={dst})")

    def _mul(self, expr: sp.Expr, dst: str) -> None:
        factors: list[sp.Expr] = []
        for factor in sp.Mul.make_args(expr):
            if factor.is_Pow and factor.exp.is_Integer and factor.exp > 0:
                factors += [factor.base] * int(factor.exp)
            else:
                factors.append(factor)
        columns = [f for f in factors if not (f.is_number or f in LENGTHS)]
        scale = sp.Mul(*[f for f in factors if f.is_number or f in LENGTHS])
        first, *rest = columns
        if _is_column(first):
            current = str(first)
        else:
            self.into(first, dst)
            current = dst
        for factor in rest:
            name, row = self._operand(factor)
            self._op(f"np.multiply({current}, {name}, out={dst})")
            current = dst
            if row:
                self._free.append(row)
        if scale == -1:
            self._op(f"np.negative({current}, out={dst})")
        elif scale != 1:
            self._op(f"np.multiply({current}, {_pycode(scale)}, out={dst})")
        elif current != dst:
            self._op(f"np.copyto({dst}, {current})")


def _is_column(expr: sp.Expr) -> bool:
    """A symbol that names a column (an angle's cos/sin or a temporary), not a link length."""
    return expr.is_Symbol and expr not in LENGTHS


def _is_scalar(expr: sp.Expr) -> bool:
    """A number or a product of link lengths: one float in the generated code."""
    return expr.free_symbols <= set(LENGTHS)


def _is_number(text: str) -> bool:
    """Printed code that is a plain number (packed as a float: struct converts ints slower)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _pycode(expr: sp.Expr) -> str:
    return sp.pycode(expr, fully_qualified_modules=False)


def _emit_many(name, doc, final, keys, shape, trig, temps, sums, used_q) -> list[str]:
    """Source lines of ``{name}_many``: the expressions on whole columns as
    :class:`_ColumnCode` (angles, their cos/sin, temporaries and entries in one workspace; every
    entry gets its row in the output's order, and one transposing copy stores them all)."""
    code = _ColumnCode()
    angles = {}
    for d in used_q:
        angles[d] = code.row(f"q{d}")
        code.lines.append(f"    np.copyto(q{d}, q[:, {int(d) - 1}])")
    for digits in sums:
        head, last = digits[:-1], digits[-1]
        first = angles[head] if head in angles else f"q[:, {int(head) - 1}]"
        angles[digits] = code.row(f"q{digits}")
        code.lines.append(f"    np.add({first}, q[:, {int(last) - 1}], out=q{digits})")
    count = len(angles)
    code.rows += 2 * count
    code.lines.append(
        f"    _cos_sin(w[:{count}], w[{count}:{2 * count}], w[{2 * count}:{3 * count}])"
    )
    order = list(angles)
    for sym, digits in trig:
        row = count + order.index(digits) + (count if sym[0] == "s" else 0)
        code.lines.append(f"    {sym} = w[{row}]")
    for temp, expr in temps:
        code.into(expr, code.row(str(temp)))
    flat = _all_indices(shape)
    base = code.rows
    code.rows += len(flat)
    runs: list[list] = []  # constant entries, as runs [start, stop, value] of equal values
    for i, k in enumerate(flat):
        expr = final[keys.index(k)] if k in keys else sp.S.Zero
        if not expr.is_number:
            code.lines.append(f"    e{i} = w[{base + i}]")
            code.into(expr, f"e{i}")
        elif runs and runs[-1][1] == i and runs[-1][2] == _pycode(expr):
            runs[-1][1] = i + 1
        else:
            runs.append([i, i + 1, _pycode(expr)])
    code.lines += [f"    w[{base + a}:{base + b}] = {value}" for a, b, value in runs]
    return [
        f"def {name}_many(q, d1, a2, a3, d4, d5, d6, out=None, work=None):",
        f'    """{doc} (N poses, q of shape (N, 6); fills ``out`` if given; ``work`` is a',
        f'    workspace of at least ({name}_many.work_rows, N) entries of q\'s dtype)."""',
        "    n = q.shape[0]",
        "    if out is None:",
        f"        out = np.empty((n, {', '.join(map(str, shape))}), dtype=q.dtype)",
        f"    w = np.empty(({code.rows}, n), dtype=q.dtype) if work is None else work[:, :n]",
        *code.lines,
        f"    out.reshape(n, {len(flat)})[...] = w[{base}:{base + len(flat)}].T",
        "    return out",
        "",
        "",
        f"{name}_many.work_rows = {code.rows}",
    ]


def _all_indices(shape: tuple[int, ...]) -> list[tuple[int, ...]]:
    return list(itertools.product(*(range(n) for n in shape)))


def _matrix_entries(M: sp.Matrix, prefix: tuple[int, ...] = ()) -> dict:
    return {(*prefix, i, j): M[i, j] for i in range(M.rows) for j in range(M.cols)}


def generate_code() -> str:
    """Source text of ``urkin/_generated/ur_kinematics.py``."""
    frames = ur_frames()
    t06 = _matrix_entries(frames[-1])
    all_frames: dict = {}
    for i, frame in enumerate(frames):
        all_frames |= _matrix_entries(frame, (i,))
    functions = [
        ("t06", "Flange pose T_0_6", t06, (4, 4)),
        ("frames", "Frames T_0_i, i = 0 … 6", all_frames, (7, 4, 4)),
        (
            "jacobian",
            "Geometric Jacobian [v; ω] of the flange origin",
            _matrix_entries(ur_geometric_jacobian()),
            (6, 6),
            ((0, 1), (3, 4)),
        ),
        (
            "position_jacobian",
            "Position Jacobian ∂p/∂q",
            _matrix_entries(ur_position_jacobian()),
            (3, 6),
        ),
    ]
    header = _HEADER + _COS_SIN
    parts = [header, *(_emit(*function) for function in functions)]
    parts.append(_emit_pose_jacobian(t06, _matrix_entries(ur_geometric_jacobian())))
    return "\n\n\n".join(part.rstrip("\n") for part in parts) + "\n"


def write_generated(path: Path | None = None) -> Path:
    """Write the generated module (to ``urkin/_generated/ur_kinematics.py`` by default)."""
    target = Path(path) if path is not None else GENERATED_PATH
    target.write_text(generate_code(), encoding="utf-8")
    return target


def main(argv: list[str] | None = None) -> int:
    """Command line: write the generated module, or ``--check`` that it is up to date."""
    parser = argparse.ArgumentParser(prog="python -m urkin.symbolic", description=__doc__)
    parser.add_argument("--check", action="store_true", help="fail if regeneration would differ")
    args = parser.parse_args(argv)
    if args.check:
        if GENERATED_PATH.read_text(encoding="utf-8") != generate_code():
            print(f"{GENERATED_PATH} is out of date: run `python -m urkin.symbolic`")
            return 1
        print(f"{GENERATED_PATH} is up to date")
        return 0
    print(f"wrote {write_generated()}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
