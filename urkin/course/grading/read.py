"""Reading a submitted notebook: which lesson it is, and what of it the grader executes.

The file is untrusted: it may be no notebook at all (a FIFO, a directory, a symlink, a 2 GB
file, JSON nested a million deep, a syntax error in every cell).  :func:`read_notebook` never
raises for such a file: :attr:`Notebook.error` says what is wrong, and the grader gives the
submission its row with that reason.

A submission is never run top to bottom.  For each exercise the grader executes only the
statements its functions need (:meth:`Notebook.plan`): the function defined in the exercise's
cell, the functions, classes, imports and assignments it uses (directly or not), top-level
``try``/``if``/``with``/``for`` blocks that define any of them, and statements that fill a
table it reads (``DH[0] = …``, ``links.append(…)``).  Calls at the top level of a cell
(``check(...)``, plots, loops that only print, ``sys.exit()``) are skipped, so demonstrations
cost nothing and cannot hang the grader.  IPython syntax (``%magic``, ``!shell``, ``obj?``) is
read as IPython reads it.

The graded function is the one defined in the exercise's cell (the cell the course notebook
gives that exercise, unless that cell still holds the stub and the function is written in
another cell; else the last definition before the exercise's ``check(...)`` cell, else the
first definition).  A later redefinition or import of the same name is not graded: it is
reported in the feedback (:attr:`Notebook.notes`).
"""

from __future__ import annotations

import ast
import errno
import json
import os
import re
import stat
import threading
from collections import OrderedDict
from dataclasses import dataclass, field
from pathlib import Path

from urkin.course.parsing import parse

__all__ = [
    "MAX_NOTEBOOK_BYTES",
    "Notebook",
    "Site",
    "exercise_cells",
    "lesson_from_filename",
    "read_notebook",
    "read_untrusted",
]

#: Largest notebook file the grader reads.
MAX_NOTEBOOK_BYTES = 20 * 2**20
#: Most code cells, characters in one cell, top-level statements and characters of code in all
#: the grader reads (a course notebook has about 60 cells and 50 000 characters; these keep the
#: grader's memory and time small whatever it is given).
MAX_CODE_CELLS = 2000
MAX_CELL_CHARACTERS = 50_000
MAX_STATEMENTS = 10_000
MAX_CODE_CHARACTERS = 1_000_000

# cell magics whose body is Python; any other cell magic (%%bash, %%html …) is not code
_PYTHON_CELL_MAGICS = {"time", "timeit", "capture", "prun", "debug", "memit", "skip"}
_BLOCKS = (ast.If, ast.Try, ast.With, ast.For, ast.While, ast.AsyncFor, ast.AsyncWith)
_BLOCKS += (ast.Match,) if hasattr(ast, "Match") else ()
_BLOCKS += (ast.TryStar,) if hasattr(ast, "TryStar") else ()


def read_untrusted(path: str | Path, limit: int = MAX_NOTEBOOK_BYTES) -> bytes:
    """The bytes of a regular file, refusing symlinks, FIFOs, devices, directories and files
    over ``limit`` bytes (:class:`ValueError` with the reason) without blocking."""
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(path, flags)
    except OSError as exc:
        if exc.errno == errno.ELOOP or os.path.islink(path):
            raise ValueError("it is a symbolic link; hand in the notebook file itself") from None
        if exc.errno == errno.EISDIR:
            raise ValueError("it is a directory, not a notebook file") from None
        raise ValueError(f"it cannot be opened ({exc.strerror})") from None
    try:
        info = os.fstat(fd)
        if stat.S_ISDIR(info.st_mode):
            raise ValueError("it is a directory, not a notebook file")
        if not stat.S_ISREG(info.st_mode):
            raise ValueError("it is not a regular file (a FIFO, a socket or a device)")
        if info.st_size > limit:
            raise ValueError(f"it is larger than {limit // 2**20} MB")
        chunks, total = [], 0
        while total <= limit:
            chunk = os.read(fd, min(1 << 20, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
        if total > limit:
            raise ValueError(f"it is larger than {limit // 2**20} MB")
        return b"".join(chunks)
    finally:
        os.close(fd)


def lesson_from_filename(path: str | Path) -> str | None:
    """The lesson a file name gives: its first two-digit number standing alone, or None.

    Examples
    --------
    >>> [lesson_from_filename(n) for n in ("02_dh.ipynb", "bob_01.ipynb", "alice~03", "hw.ipynb")]
    ['02', '01', '03', None]
    """
    match = re.search(r"(?<!\d)(\d{2})(?!\d)", Path(path).name)
    return match.group(1) if match else None


def _lesson_from_metadata(notebook: dict) -> str | None:
    meta = notebook.get("metadata")
    meta = meta.get("urkin") if isinstance(meta, dict) else None
    lesson = meta.get("lesson") if isinstance(meta, dict) else None
    if isinstance(lesson, str) and lesson.isdigit() and len(lesson) <= 3:
        return f"{int(lesson):02d}"
    return None


def _python_source(text: str) -> tuple[str | None, str | None]:
    """A cell's text as Python (IPython syntax turned into calls), or (None, why not)."""
    lines = text.split("\n")
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is not None and lines[first].lstrip().startswith("%%"):
        magic = lines[first].lstrip()[2:].split()[0] if lines[first].strip() != "%%" else ""
        if magic not in _PYTHON_CELL_MAGICS:
            return None, f"a %%{magic} cell, not Python"
        lines[first] = ""
        text = "\n".join(lines)
    try:
        from IPython.core.inputtransformer2 import TransformerManager
    except ImportError:  # read IPython's line syntax without IPython
        out = []
        for line in text.split("\n"):
            stripped = line.strip()
            if stripped.startswith(("%", "!", "?")) or (
                stripped.endswith("?") and not stripped.startswith("#")
            ):
                line = line[: len(line) - len(line.lstrip())] + "pass"
            out.append(line)
        return "\n".join(out), None
    try:
        return TransformerManager().transform_cell(text), None
    except Exception:  # IPython could not read it: let the Python parser say why
        return text, None


def _free_names(node: ast.AST) -> tuple[set[str], set[str]]:
    """Global names a statement reads, and the dotted chains it reads them through."""
    bound: set[str] = set()
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
        args = node.args
        bound |= {a.arg for a in (*args.posonlyargs, *args.args, *args.kwonlyargs) if a}
        bound |= {a.arg for a in (args.vararg, args.kwarg) if a}
    inner = node.body if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) else [node]
    declared_global: set[str] = set()
    for sub in ast.walk(ast.Module(body=inner, type_ignores=[])) if inner else []:
        if isinstance(sub, ast.Global):
            declared_global |= set(sub.names)
        elif isinstance(sub, ast.Name) and not isinstance(sub.ctx, ast.Load):
            bound.add(sub.id)
        elif isinstance(sub, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            bound.add(sub.name)
        elif isinstance(sub, (ast.Import, ast.ImportFrom)):
            bound |= {(a.asname or a.name).split(".")[0] for a in sub.names}
        elif isinstance(sub, ast.arg):
            bound.add(sub.arg)
        elif isinstance(sub, ast.ExceptHandler) and sub.name:
            bound.add(sub.name)
    if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        bound = set()  # a top-level statement's assignments are globals, not locals
    names, chains = set(), set()
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load):
            names.add(sub.id)
        elif isinstance(sub, ast.Attribute):
            parts = []
            value: ast.AST = sub
            while isinstance(value, ast.Attribute):
                parts.insert(0, value.attr)
                value = value.value
            if isinstance(value, ast.Name):
                parts.insert(0, value.id)
                chains |= {".".join(parts[: i + 1]) for i in range(1, len(parts))}
    free = names - (bound - declared_global)
    return free, {c for c in chains if c.split(".")[0] in free}


def _bound_at_top(node: ast.stmt) -> set[str]:
    """Names a top-level statement binds in the notebook's namespace."""
    found: set[str] = set()

    def visit(sub: ast.AST) -> None:
        if isinstance(sub, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            found.add(sub.name)
            return  # its body binds locals
        if isinstance(sub, (ast.Import, ast.ImportFrom)):
            found.update((a.asname or a.name).split(".")[0] for a in sub.names if a.name != "*")
        elif isinstance(sub, ast.Name) and not isinstance(sub.ctx, ast.Load):
            found.add(sub.id)
        elif isinstance(sub, ast.ExceptHandler) and sub.name:
            found.add(sub.name)
        elif isinstance(
            sub, (ast.Lambda, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)
        ):
            return
        for child in ast.iter_child_nodes(sub):
            visit(child)

    visit(node)
    return found


def _mutated(node: ast.stmt) -> str | None:
    """The name whose contents a statement changes in place: ``DH[0] = …``, ``T.fill(0)``."""
    target: ast.AST | None = None
    if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign)):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        if len(targets) == 1 and isinstance(targets[0], (ast.Subscript, ast.Attribute)):
            target = targets[0]
    elif isinstance(node, ast.Expr) and isinstance(node.value, ast.Call):
        if isinstance(node.value.func, ast.Attribute):
            target = node.value.func.value
    while isinstance(target, (ast.Subscript, ast.Attribute)):
        target = target.value
    return target.id if isinstance(target, ast.Name) else None


def _is_stub(node: ast.stmt) -> bool:
    """Whether a statement is a course stub: a function whose body (after its docstring) only
    raises NotImplementedError."""
    if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        return False
    body = node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
        body = body[1:]
    if len(body) != 1 or not isinstance(body[0], ast.Raise) or body[0].exc is None:
        return False
    raised = body[0].exc.func if isinstance(body[0].exc, ast.Call) else body[0].exc
    return isinstance(raised, ast.Name) and raised.id == "NotImplementedError"


def _written(site: Site) -> set[str]:
    """The names a statement binds or changes in place."""
    return site.binds | site.fills | ({site.mutates} if site.mutates else set())


def _filled(block: ast.stmt) -> set[str]:
    """The names whose contents the statements inside a top-level block change in place
    (``for k, v in pairs: TABLE[k] = v``), not counting those of functions it defines."""
    found: set[str] = set()
    for field_name in ("body", "orelse", "finalbody", "handlers", "cases"):
        for sub in getattr(block, field_name, None) or []:
            if isinstance(sub, (ast.ExceptHandler, *_CASES)):
                found |= _filled(sub)
                continue
            mutated = _mutated(sub)
            if mutated is not None:
                found.add(mutated)
            elif isinstance(sub, _BLOCKS):
                found |= _filled(sub)
    return found


_CASES = (ast.match_case,) if hasattr(ast, "match_case") else ()


@dataclass
class Site:
    """One top-level statement of a code cell."""

    cell: int  # 1-based position among the notebook's code cells
    index: int  # position in the cell's top-level statements
    node: ast.stmt
    kind: str  # def, class, import, assign, block, mutation, other
    binds: set[str]
    uses: set[str]
    chains: set[str]
    module: str = ""  # for ``import a.b.c`` without ``as``: "a.b.c"
    mutates: str | None = None
    fills: frozenset[str] = frozenset()  # a block's tables filled in place (``T[k] = …``)

    @property
    def line(self) -> int:
        return self.node.lineno

    def describe(self) -> str:
        return f"code cell {self.cell}, line {self.line}"


@dataclass
class Notebook:
    """What could be read from a submitted notebook."""

    path: Path
    lesson: str | None
    cells: dict[int, str] = field(default_factory=dict)  # code cell number → Python source
    cell_ids: dict[int, str] = field(default_factory=dict)
    sites: list[Site] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    error: str | None = None
    conflict: str = ""  # why the lesson cannot be told (its metadata and its name disagree)

    def sites_binding(self, name: str) -> list[Site]:
        return [s for s in self.sites if name in s.binds]

    def graded_site(self, function: str, exercise_id: str, cell_id: str | None = None):
        """The statement that defines the graded ``function`` (see the module docstring)."""
        candidates = self.sites_binding(function)
        if not candidates:
            return None
        if cell_id is not None:
            in_cell = [s for s in candidates if self.cell_ids.get(s.cell) == cell_id]
            written = [s for s in candidates if not _is_stub(s.node)]
            if in_cell and not (_is_stub(in_cell[-1].node) and written):
                return in_cell[-1]
            if in_cell:  # the exercise's cell still holds the stub: written in another cell
                candidates = written
        call = re.compile(r"""\bcheck\(\s*["']""" + re.escape(exercise_id) + r"""["']""")
        for number, source in self.cells.items():
            match = call.search(source)
            if match:
                line = source.count("\n", 0, match.start()) + 1
                before = [s for s in candidates if (s.cell, s.line) <= (number, line)]
                if before:
                    return before[-1]
                break
        return candidates[0]

    def stub_left(self, function: str, cell_id: str | None, graded: Site) -> Site | None:
        """The stub of ``function`` left in the exercise's cell (``cell_id``) when another
        definition, ``graded``, is graded instead; else None."""
        for site in self.sites_binding(function):
            if (
                site is not graded
                and cell_id is not None
                and self.cell_ids.get(site.cell) == cell_id
                and _is_stub(site.node)
            ):
                return site
        return None

    def check_call(self, exercise_id: str, graded: Site) -> tuple[int, int] | None:
        """Where the exercise's first ``check("N.M", …)`` call after its graded definition
        ``graded`` is, as (code cell, line); None where the notebook has none."""
        call = re.compile(r"""\bcheck\(\s*["']""" + re.escape(exercise_id) + r"""["']""")
        for number in sorted(n for n in self.cells if n >= graded.cell):
            source = self.cells[number]
            for match in call.finditer(source):
                line = source.count("\n", 0, match.start()) + 1
                if (number, line) > (graded.cell, graded.line):
                    return number, line
        return None

    def plan(
        self,
        roots: set[str],
        graded: dict[str, Site],
        cut: tuple[int, int] | None = None,
        notes: list[str] | None = None,
    ) -> list[Site]:
        """The statements to execute so that the functions ``roots`` exist as the notebook
        defines them, with each exercise function bound by its graded site (``graded``).

        With ``cut`` (code cell, line: where the exercise's check cell calls ``check``), a
        name bound before the cut keeps that binding: statements after it that bind or fill
        the name again (a demo cell's ``T = np.eye(4)``, a helper of the same name written
        for a later exercise) are not executed, so that the functions see what the check cell
        saw.  ``notes`` gets a sentence for each of those that would have been executed, and
        for each top-level call skipped that would have set, with ``global``, a name the
        functions read."""
        order = {id(s): i for i, s in enumerate(self.sites)}
        skipped = {
            id(s)
            for name, site in graded.items()
            for s in self.sites_binding(name)
            if order[id(s)] > order[id(site)]
        }
        late: list[Site] = []
        if cut is not None:
            seen = set().union(*(_written(s) for s in self.sites if (s.cell, s.line) < cut))
            late = [
                s
                for s in self.sites
                if (s.cell, s.line) > cut and id(s) not in skipped and _written(s) & seen
            ]
            skipped |= {id(s) for s in late}
        data_names = {n for s in self.sites if s.kind in ("assign", "block") for n in s.binds}
        needed, chains = set(roots), set()
        chosen: dict[int, Site] = {}
        changed = True
        while changed:
            changed = False
            for site in self.sites:
                if id(site) in chosen or id(site) in skipped:
                    continue
                take = False
                if site.kind == "mutation":
                    take = site.mutates in needed and site.mutates in data_names
                elif site.kind == "import" and site.module and "." in site.module:
                    root = site.module.split(".")[0]
                    plain = any(
                        s.kind == "import" and root in s.binds and not s.module for s in self.sites
                    )
                    take = root in needed and (
                        not plain
                        or any(c.startswith(site.module) for c in chains)
                        or any(site.module.startswith(c + ".") or site.module == c for c in chains)
                    )
                elif site.kind != "other":
                    take = bool(site.binds & needed) or bool(site.fills & needed & data_names)
                if take:
                    chosen[id(site)] = site
                    needed |= site.uses
                    chains |= site.chains
                    changed = True
        if notes is not None:
            for site in late:  # those that would have been executed
                if site.kind == "mutation":
                    names = sorted({site.mutates} & needed & data_names)
                elif site.kind in ("def", "class", "assign", "block"):
                    names = sorted((site.binds & needed) | (site.fills & needed & data_names))
                else:
                    names = []
                if names:
                    notes.append(
                        f"{site.describe()} binds `{names[0]}` again after the check cell of an "
                        f"exercise that uses it (code cell {cut[0]}): that exercise was graded "
                        f"with the `{names[0]}` bound above its check cell, as Restart & Run All "
                        "runs the notebook"
                    )
            for site, function, name in self._global_setters(needed):
                notes.append(
                    f"{site.describe()} calls `{function}()`, which sets the global `{name}` "
                    "the graded code reads; the grader runs no calls at the top level of a cell "
                    f"(lesson 00): bind `{name}` with an assignment (`{name} = …`) instead"
                )
        return sorted(chosen.values(), key=lambda s: order[id(s)])

    def _global_setters(self, names: set[str]) -> list[tuple[Site, str, str]]:
        """Top-level calls the grader skips of notebook functions that set, with ``global``,
        one of ``names``: (the call, the function, the name)."""
        wanted = set(names)
        setters: dict[str, str] = {}
        for site in self.sites:
            if site.kind == "def":
                for sub in ast.walk(site.node):
                    if isinstance(sub, ast.Global):
                        for name in sub.names:
                            if name in wanted:
                                setters.setdefault(site.node.name, name)
        found = []
        for site in self.sites:
            node = site.node
            if (
                site.kind == "other"
                and isinstance(node, ast.Expr)
                and isinstance(node.value, ast.Call)
                and isinstance(node.value.func, ast.Name)
                and node.value.func.id in setters
            ):
                found.append((site, node.value.func.id, setters[node.value.func.id]))
        return found

    def redefinitions(self, function: str, graded: Site) -> list[Site]:
        """Later statements that bind ``function`` again (not graded, reported)."""
        return [
            s
            for s in self.sites_binding(function)
            if (s.cell, s.index) > (graded.cell, graded.index)
        ]


#: What :func:`_facts` finds in one statement: kind, binds, uses, chains, module, mutates,
#: fills.
_Facts = tuple[str, frozenset, frozenset, frozenset, str, "str | None", frozenset]


def _facts(node: ast.stmt) -> _Facts:
    """The :class:`Site` fields of one top-level statement but its place and node."""
    site = _site(0, 0, node)
    return (
        site.kind,
        frozenset(site.binds),
        frozenset(site.uses),
        frozenset(site.chains),
        site.module,
        site.mutates,
        site.fills,
    )


class _Memo:
    """A small least-recently-used table of what was read from cells, keyed by their text
    (thread-safe).  The submissions of one lesson share most of their cells with the course
    notebook and with each other, so a shared cell is read once while it stays in the table
    (the least recently used text leaves first); only texts of up to
    :data:`_MEMO_CHARACTERS` are kept, which bounds the table's memory whatever it is given."""

    def __init__(self, size: int) -> None:
        self.size, self.table, self.lock = size, OrderedDict(), threading.Lock()

    def get(self, key: str):
        with self.lock:
            found = self.table.get(key)
            if found is not None:
                self.table.move_to_end(key)
            return found

    def put(self, key: str, value) -> None:
        if len(key) > _MEMO_CHARACTERS:
            return
        with self.lock:
            self.table[key] = value
            while len(self.table) > self.size:
                self.table.popitem(last=False)


#: The longest cell text the memo keeps (a course notebook's longest code cell has about
#: 4,000 characters), and how many texts each table keeps.
_MEMO_CHARACTERS, _MEMO_SIZE = 10_000, 512
_SOURCES, _STATEMENTS = _Memo(_MEMO_SIZE), _Memo(_MEMO_SIZE)


def _python_source_memo(text: str) -> tuple[str | None, str | None]:
    """:func:`_python_source`, remembered (:class:`_Memo`)."""
    found = _SOURCES.get(text)
    if found is None:
        found = _python_source(text)
        _SOURCES.put(text, found)
    return found


def _sites(cell: int, source: str, body: list[ast.stmt]) -> list[Site]:
    """The sites of one cell's statements ``body`` (parsed from ``source``): each
    statement's facts remembered by the cell's source (:class:`_Memo`), the nodes fresh."""
    facts = _STATEMENTS.get(source)
    if facts is None or len(facts) != len(body):
        facts = tuple(_facts(node) for node in body)
        _STATEMENTS.put(source, facts)
    return [
        Site(cell, i, node, kind, set(binds), set(uses), set(chains), module, mutates, fills)
        for i, (node, (kind, binds, uses, chains, module, mutates, fills)) in enumerate(
            zip(body, facts)
        )
    ]


def _site(cell: int, index: int, node: ast.stmt) -> Site:
    uses, chains = _free_names(node)
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        extra = [*node.decorator_list]
        if not isinstance(node, ast.ClassDef):
            extra += [*node.args.defaults, *(d for d in node.args.kw_defaults if d)]
            extra += [
                a.annotation for a in (*node.args.args, *node.args.kwonlyargs) if a.annotation
            ]
            if node.returns:
                extra.append(node.returns)
        else:
            extra += [*node.bases, *(k.value for k in node.keywords)]
        for sub in extra:
            more, more_chains = _free_names(sub)
            uses |= more
            chains |= more_chains
        kind = "class" if isinstance(node, ast.ClassDef) else "def"
        return Site(cell, index, node, kind, {node.name}, uses, chains)
    if isinstance(node, (ast.Import, ast.ImportFrom)):
        module = ""
        if isinstance(node, ast.Import) and len(node.names) == 1 and not node.names[0].asname:
            module = node.names[0].name if "." in node.names[0].name else ""
        return Site(cell, index, node, "import", _bound_at_top(node), set(), set(), module)
    mutated = _mutated(node)
    if mutated is not None:
        return Site(cell, index, node, "mutation", set(), uses, chains, mutates=mutated)
    if isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
        if isinstance(node, ast.AnnAssign) and node.value is None:
            return Site(cell, index, node, "other", set(), set(), set())
        return Site(cell, index, node, "assign", _bound_at_top(node), uses, chains)
    if isinstance(node, _BLOCKS):
        binds = _bound_at_top(node)
        return Site(cell, index, node, "block", binds, uses, chains, fills=frozenset(_filled(node)))
    return Site(cell, index, node, "other", set(), set(), set())


def _cell_text(cell: dict) -> str | None:
    source = cell.get("source", "")
    if isinstance(source, list) and all(isinstance(s, str) for s in source):
        return "".join(source)
    return source if isinstance(source, str) else None


def read_notebook(path: str | Path, lesson: str | None = None) -> Notebook:
    """Read a submitted notebook; never raises for a bad file (see :attr:`Notebook.error`).

    Parameters
    ----------
    path : str or Path
    lesson : str, optional
        The lesson to assume; by default the notebook's metadata says, then its file name
        (when they disagree and the file has a course notebook's name, ``NN_topic.ipynb``,
        none: see :attr:`Notebook.conflict`).
    """
    path = Path(path)
    notebook = Notebook(path, f"{int(lesson):02d}" if lesson is not None else None)
    try:
        data = json.loads(read_untrusted(path).decode("utf-8"))
        cells = data["cells"]
        if not isinstance(cells, list):
            raise TypeError("its cells are not a list")
    except ValueError as exc:  # includes UnicodeDecodeError and JSONDecodeError
        notebook.error = f"not a valid notebook: {exc}"
        notebook.lesson = notebook.lesson or lesson_from_filename(path)
        return notebook
    except (KeyError, TypeError, RecursionError, MemoryError) as exc:
        notebook.error = f"not a valid notebook (the file is not notebook JSON: {exc!s:.200})"
        notebook.lesson = notebook.lesson or lesson_from_filename(path)
        return notebook
    if notebook.lesson is None:
        meta, named = _lesson_from_metadata(data), lesson_from_filename(path)
        notebook.lesson = meta or named
        if meta and named and meta != named and re.match(r"\d{2}_", path.name):
            # a notebook handed in under another lesson's course name (NN_topic.ipynb, as a
            # Gradescope assignment takes it): either could be the assignment
            notebook.lesson = None
            notebook.conflict = (
                f"the notebook's metadata says lesson {meta} and its file name lesson {named}: "
                "not graded, since either could be the assignment (the instructor can pass "
                "--lesson to grade it as one of them)"
            )
        elif meta and named and meta != named:  # another number in a name a student chose
            notebook.notes.append(
                f"the notebook's metadata says lesson {meta} and its file name lesson {named}: "
                f"graded as lesson {meta} (the instructor can pass --lesson)"
            )
    number, read = 0, 0
    for cell in cells:
        if not isinstance(cell, dict) or cell.get("cell_type") != "code":
            continue
        number += 1
        text = _cell_text(cell)
        if text is None:
            notebook.notes.append(f"code cell {number} is malformed: it was skipped")
            continue
        if len(text) > MAX_CELL_CHARACTERS:
            notebook.notes.append(
                f"code cell {number} has more than {MAX_CELL_CHARACTERS} characters: skipped"
            )
            continue
        read += len(text)
        if number > MAX_CODE_CELLS or read > MAX_CODE_CHARACTERS:
            notebook.notes.append(
                f"the notebook has more than {MAX_CODE_CELLS} code cells or "
                f"{MAX_CODE_CHARACTERS} characters of code: code cell {number} and the ones "
                "after it were not read"
            )
            break
        if isinstance(cell.get("id"), str):
            notebook.cell_ids[number] = cell["id"]
        source, why_not = _python_source_memo(text)
        if source is None:
            notebook.notes.append(f"code cell {number} is {why_not}: it was skipped")
            continue
        try:
            tree = parse(source, filename=f"<cell {number}>")
        except SyntaxError as exc:
            notebook.notes.append(
                f"code cell {number} has a syntax error on line {exc.lineno}: {exc.msg}; "
                "nothing in that cell could be graded"
            )
            continue
        except (ValueError, RecursionError, MemoryError) as exc:
            notebook.notes.append(f"code cell {number} cannot be read ({exc!s:.100})")
            continue
        if len(notebook.sites) + len(tree.body) > MAX_STATEMENTS:
            notebook.notes.append(
                f"the notebook has more than {MAX_STATEMENTS} statements: code cell {number} "
                "and the ones after it were not read"
            )
            break
        notebook.cells[number] = source
        notebook.sites += _sites(number, source, tree.body)
    return notebook


def exercise_cells(course_notebook: Path) -> dict[str, str]:
    """Cell ids of the exercise cells of a course (student) notebook: function → cell id."""
    try:
        data = json.loads(course_notebook.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    found = {}
    stub = re.compile(r"""raise NotImplementedError\(["']Exercise [\d.]+: write (\w+)""")
    for cell in data.get("cells", []):
        text = _cell_text(cell) or ""
        match = stub.search(text)
        if match and isinstance(cell.get("id"), str):
            found[match.group(1)] = cell["id"]
    return found
