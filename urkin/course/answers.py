"""What counts as urkin's own answer to an exercise, and how it is kept from the submission.

An exercise declares its answer as library concepts (:attr:`Exercise.answer`): functions,
classes or whole modules, such as ``urkin.kinematics.fk`` or the generated kinematics module.
A submission could reach the same answer by another route — another urkin function that calls
it, an alias, a class that wraps it — so the hidden set is the declared names **and every
library function, class or constant whose code uses one of them**, found by reading the
library's source (imports, aliases and re-exports resolved), recomputed whenever the library
changes.  Nothing here lists private names.

While an exercise is graded, the submission sees a *view* of urkin (:meth:`Answer.write_view`):
a copy of the package in which every hidden name is a :class:`~urkin.course.hidden.Hidden`
stand-in and the course wing is reduced to what student code may import.  In the sandbox the
view is mounted over urkin's own directory, so no route — an import, a reload, a subprocess,
reading the file — reaches the real code.  A notebook's check cell hides the same names in
the running kernel for the length of each call (:meth:`Answer.hidden_in`).
"""

from __future__ import annotations

import ast
import functools
import hashlib
import py_compile
import shutil
import sys
import types
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from urkin.course.hidden import Hidden

__all__ = ["Answer", "answer_for", "library_modules"]

PACKAGE = Path(__file__).resolve().parents[1]  # the urkin package directory

# Course modules a submission may import while graded (the rest of the wing — lessons, checks,
# grader, builder — is not in the view at all).
_COURSE_MODULES = (
    "urkin.course.display",
    "urkin.course.hidden",
    "urkin.course.lab",
    "urkin.course.seeds",
    "urkin.course.wire",
    "urkin.course.watch",
    "urkin.course.grading.child",
)
_NOT_IN_VIEW = ("urkin.cli", "urkin.__main__")
# The grading runtime inside the view: copied as it is, never hidden (it computes no answer; the
# library functions it calls are looked up when called, so they are the view's stand-ins).
_RUNTIME = (
    "urkin.course.grading.child",
    "urkin.course.hidden",
    "urkin.course.wire",
    "urkin.course.watch",
)

_STUDENT_COURSE_INIT = '''"""The course wing as graded code sees it: check() does nothing."""

import importlib

_MODULES = ("display", "hidden", "lab", "seeds", "wire")
_NAMES = {"below": "display", "fk_lab": "lab", "ik_lab": "lab"}


def check(*args, **kwargs):
    """Does nothing while a submission is graded (the grader runs the checks itself)."""
    return None


def __getattr__(name):
    if name in _MODULES:
        return importlib.import_module(f"urkin.course.{name}")
    if name in _NAMES:
        return getattr(importlib.import_module(f"urkin.course.{_NAMES[name]}"), name)
    raise AttributeError(f"urkin.course has no {name!r} while a submission is graded")
'''


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def library_modules() -> dict[str, Path]:
    """The modules a submission's view of urkin is made of: name → source file."""
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        name = _module_name(path)
        if name in _NOT_IN_VIEW or "__pycache__" in path.parts:
            continue
        if name.startswith("urkin.course") and name not in _COURSE_MODULES:
            continue
        found[name] = path
    return found


@dataclass
class _Module:
    name: str
    package: str
    tree: ast.Module
    items: dict[str, list[ast.stmt]]  # top-level name → the statements that bind it
    aliases: dict[str, tuple[str, ...]]  # name → ("module", m) or ("from", m, attribute)


def _import_aliases(nodes: Iterable[ast.AST], package: str) -> dict[str, tuple[str, ...]]:
    aliases: dict[str, tuple[str, ...]] = {}
    for node in nodes:
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname:
                    aliases[alias.asname] = ("module", alias.name)
                else:
                    root = alias.name.split(".")[0]
                    aliases[root] = ("module", root)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                base = f"{parent}.{base}" if base else parent
            for alias in node.names:
                aliases[alias.asname or alias.name] = ("from", base, alias.name)
    return aliases


def _bound_names(node: ast.stmt) -> list[str]:
    if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
        return [node.name]
    if isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        return [n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)]
    return []


@functools.cache
def _parse(name: str, path: Path, stamp: float) -> _Module:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    items: dict[str, list[ast.stmt]] = {}
    for node in tree.body:
        for bound in _bound_names(node):
            items.setdefault(bound, []).append(node)
    aliases = _import_aliases(
        (n for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))), package
    )
    return _Module(name, package, tree, items, aliases)


def _modules() -> dict[str, _Module]:
    return {
        name: _parse(name, path, path.stat().st_mtime) for name, path in library_modules().items()
    }


class _Resolver:
    """Resolves names in the library's code to the top-level objects they denote."""

    def __init__(self, modules: dict[str, _Module]) -> None:
        self.modules = modules

    def canonical(self, target: tuple[str, ...], depth: int = 0) -> tuple[str, ...] | None:
        if depth > 20:
            return None
        if target[0] == "module":
            return target if target[1] in self.modules else None
        if target[0] == "object":
            return target
        _, module, attribute = target
        if f"{module}.{attribute}" in self.modules:
            return ("module", f"{module}.{attribute}")
        found = self.modules.get(module)
        if found is None:
            return None
        if attribute in found.items:
            return ("object", module, attribute)
        if attribute in found.aliases:
            return self.canonical(found.aliases[attribute], depth + 1)
        return None

    def refs(self, module: _Module, node: ast.AST) -> set[tuple[str, str]]:
        """Top-level library objects that the code of ``node`` uses."""
        local = _import_aliases(
            (n for n in ast.walk(node) if isinstance(n, (ast.Import, ast.ImportFrom))),
            module.package,
        )
        found: set[tuple[str, str]] = set()
        for sub in ast.walk(node):
            chain: list[str] = []
            if isinstance(sub, ast.Name):
                chain = [sub.id]
            elif isinstance(sub, ast.Attribute):
                value: ast.AST = sub
                while isinstance(value, ast.Attribute):
                    chain.insert(0, value.attr)
                    value = value.value
                if not isinstance(value, ast.Name):
                    continue
                chain.insert(0, value.id)
            else:
                continue
            target = self._resolve(module, chain, local)
            if target is not None:
                found.add(target)
        return found

    def _resolve(self, module: _Module, chain: list[str], local: dict) -> tuple[str, str] | None:
        head = chain[0]
        if head in local:
            target = self.canonical(local[head])
        elif head in module.aliases:
            target = self.canonical(module.aliases[head])
        elif head in module.items:
            target = ("object", module.name, head)
        else:
            return None
        for attribute in chain[1:]:
            if target is None or target[0] != "module":
                break
            target = self.canonical(("from", target[1], attribute))
        if target is None or target[0] != "object":
            return None
        return (target[1], target[2])


def _declared(target: Any, modules: dict[str, _Module]) -> set[tuple[str, str]]:
    """The (module, name) pairs one entry of ``Exercise.answer`` declares."""
    if isinstance(target, types.ModuleType):
        name = target.__name__
        if name not in modules:
            raise ValueError(f"{name} is not a module of the library")
        return {(name, item) for item in modules[name].items}
    if isinstance(target, str):
        module, _, item = target.rpartition(".")
        if target in modules:
            return {(target, i) for i in modules[target].items}
    else:
        module, item = getattr(target, "__module__", None), getattr(target, "__name__", None)
    if module not in modules or item not in modules[module].items:
        raise ValueError(f"{target!r} is not a top-level name of a library module")
    if item.startswith("_"):
        raise ValueError(f"declare answers by public names or modules, not {module}.{item}")
    return {(module, item)}


@dataclass(frozen=True)
class Answer:
    """urkin's own answer to one exercise: the hidden names, and how to hide them."""

    exercise: str
    hidden: frozenset[tuple[str, str]]

    def names(self) -> list[str]:
        """The hidden names, dotted, sorted."""
        return sorted(f"{m}.{n}" for m, n in self.hidden)

    @contextmanager
    def hidden_in(self, namespace: dict[str, Any]) -> Iterator[None]:
        """Hide the answer in this process — in every loaded urkin module and in
        ``namespace`` — until the block ends."""
        originals: dict[int, tuple[str, Any]] = {}
        for module_name, item in self.hidden:
            module = sys.modules.get(module_name)
            if module is not None and item in vars(module):
                value = vars(module)[item]
                originals[id(value)] = (f"{module_name}.{item}", value)
        patched: list[tuple[dict, str, Any]] = []
        spaces = [
            vars(module)
            for name, module in list(sys.modules.items())
            if module is not None
            and (name == "urkin" or name.startswith("urkin."))
            and (not name.startswith("urkin.course") or name in (*_COURSE_MODULES, "urkin.course"))
        ]
        for space in [*spaces, namespace]:
            for key, value in list(space.items()):
                entry = originals.get(id(value))
                if entry is not None and entry[1] is value:
                    patched.append((space, key, value))
                    space[key] = Hidden(entry[0], self.exercise)
        try:
            yield
        finally:
            for space, key, value in patched:
                space[key] = value

    def key(self) -> str:
        """A name for this answer's view that changes when the library's source changes."""
        digest = hashlib.sha256(self.exercise.encode())
        for name in self.names():
            digest.update(name.encode() + b";")
        for name, path in sorted(library_modules().items()):
            digest.update(name.encode() + path.read_bytes())
        digest.update(sys.version.encode())
        return f"{self.exercise}-{digest.hexdigest()[:24]}"

    def write_view(self, into: Path) -> Path:
        """Write the copy of urkin a submission sees while this exercise is graded (see the
        module docstring) into ``into/urkin``, compiled; returns ``into``."""
        target = into / "urkin"
        if target.exists():
            shutil.rmtree(target)
        modules = _modules()
        for name, path in library_modules().items():
            out = target / path.relative_to(PACKAGE)
            out.parent.mkdir(parents=True, exist_ok=True)
            hidden_here = {item for module, item in self.hidden if module == name}
            if hidden_here:
                out.write_text(self._rewrite(modules[name], hidden_here), encoding="utf-8")
            else:
                shutil.copyfile(path, out)
        (target / "course" / "__init__.py").write_text(_STUDENT_COURSE_INIT, encoding="utf-8")
        (target / "course" / "grading" / "__init__.py").write_text("", encoding="utf-8")
        for source in sorted(target.rglob("*.py")):
            py_compile.compile(
                str(source),
                doraise=True,
                invalidation_mode=py_compile.PycInvalidationMode.UNCHECKED_HASH,
            )
        return into

    def _rewrite(self, module: _Module, hidden_here: set[str]) -> str:
        """The module's source with hidden names replaced by stand-ins, and any other
        top-level statement that uses them dropped."""
        resolver = _Resolver(_modules())
        body: list[ast.stmt] = []
        for node in module.tree.body:
            bound = _bound_names(node)
            if bound and set(bound) <= hidden_here:
                for name in bound:
                    body.append(
                        ast.parse(
                            f"{name} = _Hidden({module.name + '.' + name!r}, {self.exercise!r})"
                        ).body[0]
                    )
                continue
            if (
                module.name not in _RUNTIME  # the grader's own modules keep every statement
                and not isinstance(node, (ast.Import, ast.ImportFrom))
                and resolver.refs(module, node) & self.hidden
            ):
                continue  # a statement that would use a hidden name while importing
            body.append(node)
        first = 0
        while first < len(body) and (
            (isinstance(body[first], ast.Expr) and isinstance(body[first].value, ast.Constant))
            or (isinstance(body[first], ast.ImportFrom) and body[first].module == "__future__")
        ):
            first += 1
        body.insert(first, ast.parse("from urkin.course.hidden import Hidden as _Hidden").body[0])
        return ast.unparse(ast.fix_missing_locations(ast.Module(body=body, type_ignores=[])))


@functools.lru_cache(maxsize=4)
def _uses(stamp: str) -> tuple[dict, dict]:
    """What each top-level item of the library uses, and what uses it (for one source stamp)."""
    modules = _modules()
    resolver = _Resolver(modules)
    uses = {
        (module.name, item): set().union(*(resolver.refs(module, node) for node in nodes))
        for module in modules.values()
        if module.name not in _RUNTIME
        for item, nodes in module.items.items()
    }
    referrers: dict[tuple[str, str], set[tuple[str, str]]] = {}
    for key, refs in uses.items():
        for ref in refs:
            referrers.setdefault(ref, set()).add(key)
    return uses, referrers


def _closure(declared: set[tuple[str, str]], stamp: str) -> set[tuple[str, str]]:
    uses, referrers = _uses(stamp)
    hidden = set(declared)
    changed = True
    while changed:
        changed = False
        for key, refs in uses.items():
            if key in hidden:
                continue
            # upward: code that uses a hidden name computes the answer too; downward: a
            # private helper that only hidden code uses is part of the answer
            private_helper = key[1].startswith("_") and not key[1].startswith("__")
            if refs & hidden or (
                private_helper and referrers.get(key) and referrers[key] <= hidden
            ):
                hidden.add(key)
                changed = True
    return hidden


def _stamp() -> str:
    digest = hashlib.sha256()
    for name, path in sorted(library_modules().items()):
        digest.update(f"{name}:{path.stat().st_mtime_ns}:{path.stat().st_size};".encode())
    return digest.hexdigest()


def answer_for(exercise: Any) -> Answer:
    """The :class:`Answer` of an exercise (cached while the library's source is unchanged)."""
    return _answer(exercise.id, tuple(exercise.answer), _stamp())


@functools.lru_cache(maxsize=256)
def _answer(exercise_id: str, declared: tuple[Any, ...], stamp: str) -> Answer:
    modules = _modules()
    names: set[tuple[str, str]] = set()
    for target in declared:
        names |= _declared(target, modules)
    return Answer(exercise_id, frozenset(_closure(names, stamp)))
