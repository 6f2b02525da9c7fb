"""Reading a submitted notebook safely: its lesson, and the definitions it makes.

A submission is never run top to bottom.  Only its *definitions* are executed: imports,
``def`` and ``class`` statements, and those assignments to plain names that the exercise
functions need (directly or through other definitions).  Calls at the top level of a cell
(``check(...)``, ``print``, plotting, loops, ``sys.exit()``) are skipped, so demonstrations and
stray statements cannot hang or end the grader, and slow demonstrations cost nothing.
"""

from __future__ import annotations

import ast
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "Statement",
    "Submission",
    "lesson_from_filename",
    "lesson_of",
    "needed_statements",
    "read_submission",
]

_KEPT = (ast.Import, ast.ImportFrom, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)
_MAGIC = re.compile(r"^\s*[%!?]")


@dataclass(frozen=True)
class Statement:
    """One top-level statement of a code cell, ready to be compiled."""

    cell: int  # 1-based position among the notebook's code cells
    source: str  # the whole cell, magics commented out (for line numbers)
    node: ast.stmt
    kind: str  # "definition" or "assignment"

    @property
    def filename(self) -> str:
        return f"<submission cell {self.cell}>"

    @property
    def binds(self) -> set[str]:
        """Names the statement binds at the top level."""
        node = self.node
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            return {node.name}
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return {(a.asname or a.name).split(".")[0] for a in node.names}
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        return {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}

    @property
    def uses(self) -> set[str]:
        """Global names the statement may read: for a function or class, the names it reads
        that it does not bind itself (parameters and local assignments are not globals)."""
        loaded = {
            n.id
            for n in ast.walk(self.node)
            if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)
        }
        if not isinstance(self.node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            return loaded
        declared_global = {
            name for n in ast.walk(self.node) if isinstance(n, ast.Global) for name in n.names
        }
        bound = {
            n.id
            for n in ast.walk(self.node)
            if isinstance(n, ast.Name) and not isinstance(n.ctx, ast.Load)
        } | {
            a.arg
            for n in ast.walk(self.node)
            if isinstance(n, ast.arguments)
            for a in (*n.posonlyargs, *n.args, *n.kwonlyargs, n.vararg, n.kwarg)
            if a
        }
        return loaded - (bound - declared_global)

    def compile(self):
        module = ast.Module(body=[self.node], type_ignores=[])
        return compile(module, self.filename, "exec")


@dataclass
class Submission:
    """What could be read from a notebook file."""

    path: Path
    lesson: str | None
    statements: list[Statement] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # problems worth telling the student
    error: str | None = None  # set when the file cannot be read as a notebook at all


def lesson_from_filename(path: Path) -> str | None:
    """The lesson a file name gives, or None.

    Examples
    --------
    >>> [lesson_from_filename(Path(n)) for n in ("02_dh_fk.ipynb", "bob_01.ipynb", "hw.ipynb")]
    ['02', '01', None]
    """
    match = re.search(r"(?:^|[_\-\s])(\d{2})(?=[_\-.\s])", path.name)
    return match.group(1) if match else None


def _lesson_from_metadata(notebook: dict) -> str | None:
    meta = notebook.get("metadata", {}).get("urkin", {})
    lesson = meta.get("lesson") if isinstance(meta, dict) else None
    if isinstance(lesson, str) and lesson.isdigit():
        return f"{int(lesson):02d}"
    return None


def lesson_of(path: str | Path, lesson: str | None = None) -> str | None:
    """Two-digit lesson of a notebook: ``lesson`` if given, else its metadata, else its name."""
    if lesson is not None:
        return f"{int(lesson):02d}"
    path = Path(path)
    try:
        notebook = json.loads(path.read_text(encoding="utf-8"))
        from_metadata = _lesson_from_metadata(notebook) if isinstance(notebook, dict) else None
    except (OSError, ValueError, AttributeError):
        from_metadata = None
    return from_metadata or lesson_from_filename(path)


def _cell_source(cell: dict) -> str:
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else str(source)


def _is_plain_assignment(node: ast.stmt) -> bool:
    def plain(target: ast.expr) -> bool:
        if isinstance(target, ast.Name):
            return True
        if isinstance(target, (ast.Tuple, ast.List)):
            return all(plain(t) for t in target.elts)
        return False

    if isinstance(node, ast.Assign):
        return all(plain(t) for t in node.targets)
    if isinstance(node, ast.AnnAssign):
        return node.value is not None and isinstance(node.target, ast.Name)
    return False


def read_submission(path: str | Path, lesson: str | None = None) -> Submission:
    """Read a notebook and extract the statements the grader may execute.

    Parameters
    ----------
    path : str or Path
        The ``.ipynb`` file.
    lesson : str, optional
        Lesson number to assume; otherwise taken from the notebook's metadata, then from the
        file name.

    Returns
    -------
    Submission
        Never raises for a bad notebook: :attr:`Submission.error` says what is wrong.
    """
    path = Path(path)
    submission = Submission(path, lesson or lesson_from_filename(path))
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        submission.error = f"cannot read the file: {exc}"
        return submission
    try:
        notebook = json.loads(text)
        cells = notebook["cells"]
        if not isinstance(cells, list):
            raise TypeError("cells is not a list")
    except (json.JSONDecodeError, KeyError, TypeError) as exc:
        submission.error = f"not a valid notebook (the file is not notebook JSON: {exc})"
        return submission
    if lesson is None:
        submission.lesson = _lesson_from_metadata(notebook) or submission.lesson
    code_cells = [c for c in cells if isinstance(c, dict) and c.get("cell_type") == "code"]
    for number, cell in enumerate(code_cells, start=1):
        lines = _cell_source(cell).splitlines()
        source = "\n".join("# " + line if _MAGIC.match(line) else line for line in lines)
        try:
            tree = ast.parse(source, filename=f"<submission cell {number}>")
        except SyntaxError as exc:
            submission.notes.append(
                f"code cell {number} has a syntax error on line {exc.lineno}: {exc.msg}; "
                "nothing in that cell could be graded"
            )
            continue
        for node in tree.body:
            if isinstance(node, _KEPT):
                submission.statements.append(Statement(number, source, node, "definition"))
            elif _is_plain_assignment(node):
                submission.statements.append(Statement(number, source, node, "assignment"))
    return submission


def needed_statements(statements: list[Statement], roots: set[str]) -> list[Statement]:
    """The statements to execute for functions named ``roots``: every import, ``def`` and
    ``class``, and the assignments those (transitively) read, in their original order."""
    needed = set(roots)
    for statement in statements:
        if statement.kind == "definition":
            needed |= statement.uses
    changed = True
    while changed:
        changed = False
        for statement in statements:
            if statement.kind == "assignment" and statement.binds & needed:
                new = statement.uses - needed
                if new:
                    needed |= new
                    changed = True
    return [s for s in statements if s.kind == "definition" or s.binds & needed]
