"""Mutation testing of the checks: automatically mutated solutions must lose points.

Each exercise's solution function (from the solution notebook, the only copy of it) is mutated
one small change at a time — a flipped sign, a shifted index, a transposed matrix, angles taken
as degrees.  A mutant whose answers differ from the solution's on the inputs the checks use
must lose points; a mutant whose answers are identical there is equivalent and is skipped.
Every mutant is checked in-process, and one mutant of each exercise also through the isolated
grader.
"""

from __future__ import annotations

import ast
import copy
import json
import textwrap

import numpy as np
import pytest

from tests.namespaces import solution_namespace, variant
from tests.notebooks import solution_path, student_notebook, write
from urkin.course.answers import answer_for
from urkin.course.build import BEGIN, END
from urkin.course.exercise import run_exercise
from urkin.course.grading import Grader
from urkin.course.lessons import lessons
from urkin.course.submission import LocalSubmission

SEEDS = (0, 5)
MAX_MUTANTS = 10
# exercises whose right answer is not unique (an IK solution, a direction up to its sign): a
# mutant that answers otherwise but still reaches every target, or points the other way, is
# not wrong; a pick-and-place task (10.3) is judged by replaying it, and many tasks are right
NOT_UNIQUE = {"4.7", "5.2", "5.3", "6.3", "10.3"}


def _solution_source(number: str, function: str) -> str:
    notebook = json.loads(solution_path(number).read_text(encoding="utf-8"))
    for cell in notebook["cells"]:
        text = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
        if cell["cell_type"] == "code" and f"def {function}(" in text and BEGIN in text:
            return "\n".join(line for line in text.split("\n") if line.strip() not in (BEGIN, END))
    raise LookupError(function)


class _Mutator:
    """All single-point mutants of one function definition."""

    def __init__(self, source: str, function: str) -> None:
        self.tree = ast.parse(source)
        self.function = function
        self.definition = next(
            n for n in self.tree.body if isinstance(n, ast.FunctionDef) and n.name == function
        )

    def _body_nodes(self):
        body = self.definition.body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # not the docstring
        for statement in body:
            yield from ast.walk(statement)

    def mutants(self) -> list[tuple[str, str]]:
        found = []
        nodes = list(self._body_nodes())
        for index, node in enumerate(nodes):
            if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
                found.append(("flipped sign", index, "binop"))
            if (
                isinstance(node, ast.Subscript)
                and isinstance(node.slice, ast.Constant)
                and isinstance(node.slice.value, int)
            ):
                found.append(("shifted index", index, "index"))
        found.append(("transposed answer", -1, "transpose"))
        parameters = [a.arg for a in self.definition.args.args]
        angles = [
            p for p in parameters if p in ("theta", "q", "angle", "alpha", "angles_deg", "yaw_w")
        ]
        if angles:
            found.append((f"{angles[0]} taken as degrees", -1, "degrees:" + angles[0]))
        out = []
        for label, index, kind in found:
            source = self._apply(nodes, index, kind)
            if source is not None:
                out.append((f"{label} #{index}" if index >= 0 else label, source))
        # spread the choice over the function when there are many
        step = max(1, len(out) // MAX_MUTANTS)
        return out[::step][:MAX_MUTANTS]

    def _apply(self, nodes, index: int, kind: str) -> str | None:
        tree = copy.deepcopy(self.tree)
        definition = next(
            n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == self.function
        )
        mutable = list(_Mutator._walk_body(definition))
        if kind == "binop":
            node = mutable[index]
            node.op = ast.Sub() if isinstance(node.op, ast.Add) else ast.Add()
        elif kind == "index":
            node = mutable[index]
            value = node.slice.value
            node.slice = ast.Constant(value + 1 if value >= 0 else value - 1)
        elif kind == "transpose":
            definition.name = "_original_" + self.function
            wrapper = ast.parse(
                f"def {self.function}(*args, **kwargs):\n"
                f"    return np.asarray(_original_{self.function}(*args, **kwargs)).T[::-1]\n"
            ).body[0]
            tree.body.append(wrapper)
        elif kind.startswith("degrees:"):
            name = kind.split(":", 1)[1]
            first = 1 if (definition.body and isinstance(definition.body[0], ast.Expr)) else 0
            definition.body.insert(
                first, ast.parse(f"{name} = np.radians(np.asarray({name}, dtype=float))").body[0]
            )
        return ast.unparse(ast.fix_missing_locations(tree))

    @staticmethod
    def _walk_body(definition):
        body = definition.body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]
        for statement in body:
            yield from ast.walk(statement)


class _Recording(LocalSubmission):
    """A local submission that remembers every call of one function and its answer."""

    def __init__(self, namespace, function, hide, record):
        super().__init__(namespace, hide=hide)
        self.function, self.record = function, record

    def spy(self, name, watched, *args, **kwargs):
        value, calls = super().spy(name, watched, *args, **kwargs)
        if name == self.function:
            self.record.append((args, kwargs, value))
        return value, calls


def _namespace(number: str) -> dict:
    return solution_namespace(number)


def _answers_differ(a, b) -> bool:
    if isinstance(a, (str, bytes)) or isinstance(b, (str, bytes)):
        return type(a) is not type(b) or a != b
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):  # e.g. a task's steps
        return len(a) != len(b) or any(_answers_differ(x, y) for x, y in zip(a, b))
    try:
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    except (TypeError, ValueError):
        return bool(np.any(a != b))
    return a.shape != b.shape or not np.allclose(a, b, rtol=0, atol=1e-10, equal_nan=True)


def _cases():
    for number, each in lessons().items():
        for ex in each.exercises:
            try:
                source = _solution_source(number, ex.function)
            except LookupError:
                continue
            for label, mutant in _Mutator(source, ex.function).mutants():
                yield pytest.param(number, ex, mutant, id=f"{ex.id}-{label}")


@pytest.mark.parametrize(("number", "ex", "mutant"), list(_cases()))
def test_a_mutated_solution_loses_points(number, ex, mutant):
    hide = answer_for(ex).hidden_in
    for seed in SEEDS:
        original_calls: list = []
        reference = _Recording(_namespace(number), ex.function, hide, original_calls)
        assert run_exercise(ex, reference, seed).status == "passed"
        mutated_namespace = variant(number, ex.id, mutant)
        result = run_exercise(ex, LocalSubmission(mutated_namespace, hide=hide), seed)
        if result.earned < result.points or ex.id in NOT_UNIQUE:
            return
        # full marks: fine only if the mutant answers exactly as the solution on those inputs
        probe = LocalSubmission(mutated_namespace, hide=hide)
        for args, kwargs, value in original_calls:
            try:
                mutated = probe.call(ex.function, *args, **kwargs)
            except Exception:
                pytest.fail("the mutant raises on an input the checks used yet earns full marks")
            if _answers_differ(mutated, value):
                pytest.fail(
                    f"a mutant that answers differently keeps full marks:\n{mutant}\n"
                    f"inputs {args}: solution {value}, mutant {mutated}"
                )
    # equivalent on every input the checks use: nothing to catch


def test_one_mutant_of_each_exercise_loses_points_through_the_grader(tmp_path):
    chosen = {}
    for param in _cases():
        number, ex, mutant = param.values
        if ex.id not in chosen and "flipped sign" in param.id:
            chosen[ex.id] = (number, ex, mutant)
    with Grader(seed=7, time_limit=120.0) as grader:  # only a guard against hangs
        for exercise_id, (number, ex, mutant) in chosen.items():
            source = textwrap.dedent(mutant)
            path = write(
                student_notebook(number, {ex.function: source}),
                tmp_path / f"mutant_{exercise_id}_{number}.ipynb",
            )
            (result,) = grader.grade(path, exercises=[exercise_id]).exercises
            reference = run_exercise(
                ex,
                LocalSubmission(variant(number, ex.id, source), hide=answer_for(ex).hidden_in),
                7,
            )
            assert result.earned == reference.earned, (exercise_id, result.report())
