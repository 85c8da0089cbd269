"""The package layout: stages import only earlier stages, no import cycles, no private names across modules.

The stage order (README "Layout"): motion → geometry/optimize/lifttable →
reverse, toolpath → nc → post/export/plots/report/verify → spec, sizing, dask_batch → cli,
on top of the foundation modules (errors, inputs, verdict).  Imports inside ``if
TYPE_CHECKING:`` are annotations only and do not count; imports inside
functions (lazy imports) do.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "camcam"

#: Rank of each top-level package or module of camcam: an import may only go to the same or a lower rank.
RANK = {
    "__init__": 0, "errors": 0, "inputs": 0, "verdict": 0, "lazy": 0, "workers": 0, "interrupts": 0, "data": 0,
    "advice": 0,
    "motion": 1,
    "geometry": 2, "optimize": 2, "lifttable": 2,
    "reverse": 3, "toolpath": 3, "dynamics": 3, "inspect": 3,
    "nc": 4,
    "post": 5, "export": 5, "plots": 5, "report": 5, "verify": 5,
    "spec": 6, "sizing": 6, "dask_batch": 6,
    "flow": 7, "cli": 7, "__main__": 7,
}


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_type_checking(node: ast.If) -> bool:
    t = node.test
    return (isinstance(t, ast.Name) and t.id == "TYPE_CHECKING") or (
        isinstance(t, ast.Attribute) and t.attr == "TYPE_CHECKING")


def _imports(tree: ast.AST):
    """(module imported, names imported, line) for every runtime import in ``tree``."""
    skip: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and _is_type_checking(node):
            skip.update(id(n) for b in node.body for n in ast.walk(b))
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.module, [a.name for a in node.names], node.lineno
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, [], node.lineno


def _graph():
    modules = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        modules[_module_name(path)] = (path, list(_imports(ast.parse(path.read_text(encoding="utf-8")))))
    return modules


MODULES = _graph()


def _top(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def test_every_package_has_a_rank():
    assert {_top(m) for m in MODULES} <= set(RANK)


def test_stage_order():
    bad = []
    for name, (path, imports) in MODULES.items():
        src = _top(name)
        for target, _, line in imports:
            if target.split(".")[0] != "camcam":
                continue
            dst = _top(target)
            if RANK[dst] > RANK[src]:
                bad.append(f"{path.relative_to(PACKAGE.parent)}:{line} ({src}, rank {RANK[src]}) imports {target} "
                           f"({dst}, rank {RANK[dst]})")
    assert not bad, "\n".join(bad)


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` as a list of nodes, or None (iterative DFS with colours)."""
    colour = dict.fromkeys(graph, 0)
    for root in sorted(graph):
        if colour[root]:
            continue
        stack = [(root, iter(sorted(graph[root])))]
        path = [root]
        colour[root] = 1
        while stack:
            node, children = stack[-1]
            for child in children:
                if colour.get(child, 2) == 1:
                    return path[path.index(child):] + [child]
                if colour.get(child, 2) == 0:
                    colour[child] = 1
                    path.append(child)
                    stack.append((child, iter(sorted(graph[child]))))
                    break
            else:
                colour[node] = 2
                stack.pop()
                path.pop()
    return None


def _resolve(importer: str, target: str, names: list[str]) -> set[str]:
    """The camcam modules an import statement loads (``from pkg import mod`` loads pkg.mod).

    A package that contains the importer is left out: Python has imported it
    already (a parent is always imported before its modules).
    """
    out = {target} if target in MODULES and not importer.startswith(target + ".") else set()
    out |= {f"{target}.{n}" for n in names if f"{target}.{n}" in MODULES}
    return out


def test_no_module_cycle():
    graph = {name: set() for name in MODULES}
    for name, (_, imports) in MODULES.items():
        for target, names, _ in imports:
            graph[name] |= _resolve(name, target, names) - {name}
    assert _cycle(graph) is None


def test_no_package_cycle():
    graph: dict[str, set[str]] = {}
    for name, (_, imports) in MODULES.items():
        src = _top(name)
        graph.setdefault(src, set())
        for target, _, _ in imports:
            if target.split(".")[0] == "camcam" and _top(target) != src:
                graph[src].add(_top(target))
    assert _cycle(graph) is None


def test_no_private_names_across_modules():
    bad = [f"{path.relative_to(PACKAGE.parent)}:{line} imports {n} from {target}"
           for name, (path, imports) in MODULES.items()
           for target, names, line in imports
           if target.startswith("camcam") and target != name
           for n in names if n.startswith("_") and not n.endswith("__")]
    assert not bad, "\n".join(bad)


def test_the_flow_does_not_reach_into_the_command_line():
    """`camcam.flow` (the Python face, :func:`camcam.flow.run_job`) runs without the CLI: the commands call it,
    never the other way round (issue 44: the CLI only parses, calls and prints)."""
    bad = [f"{path.relative_to(PACKAGE.parent)}:{line} imports {target}"
           for name, (path, imports) in MODULES.items() if _top(name) == "flow"
           for target, _, line in imports if target.startswith("camcam.cli")]
    assert not bad, "\n".join(bad)


#: File names that stand in more than one place on purpose, each with the places and why (issue 44: a newcomer
#: guesses a module from its name, so any other shared name is a test failure; name the new module for what it
#: holds instead).
PARALLEL_NAMES = {
    # the command line is one module per command, beside the spec table or the stage of the same name
    "fit.py": ({"cli/fit.py", "reverse/fit.py"}, "`camcam fit`'s command line; reverse design's NURBS fit"),
    "motion.py": ({"cli/motion.py", "spec/motion.py"}, "`camcam motion`'s command line; the [motion] table's reader"),
    "optimize.py": ({"cli/optimize.py", "spec/optimize.py"}, "`camcam optimize`'s command line; the [optimize] table's reader"),
    "reverse.py": ({"cli/reverse.py", "plots/reverse.py"}, "`camcam reverse`'s command line; its plot"),
    "size.py": ({"cli/size.py", "spec/size.py"}, "`camcam size`'s command line; the [size] table's reader"),
    # the spec's table readers are named after their tables
    "stock.py": ({"spec/stock.py", "nc/stock.py"}, "the [stock] table's reader; the NC job's blank"),
    "inspection.py": ({"spec/inspection.py", "report/inspection.py"},
                      "the [inspection] table's reader; the run report's inspection table"),
    # one module per cam kind, in the forward and the reverse direction
    "cylindrical.py": ({"geometry/cylindrical.py", "reverse/cylindrical.py"}, "a barrel cam built; a barrel cam measured"),
    "disc.py": ({"geometry/disc.py", "reverse/disc.py"}, "a disc cam built; a disc cam measured"),
    # pending: nc/sweep.py (the material check's sweep) is being moved out of nc/ by its owner
    "sweep.py": ({"sizing/sweep.py", "nc/sweep.py"}, "pending: the sizing sweep; nc/sweep.py is moving to verify/"),
}


def test_module_names_are_unique_unless_parallel():
    """No two modules share a file name, except the parallel ones listed in PARALLEL_NAMES."""
    places: dict[str, set[str]] = {}
    for path in PACKAGE.rglob("*.py"):
        if path.name != "__init__.py":
            places.setdefault(path.name, set()).add(path.relative_to(PACKAGE).as_posix())
    bad = [f"{name}: {sorted(where)}" for name, where in sorted(places.items())
           if len(where) > 1 and not where <= PARALLEL_NAMES.get(name, (set(),))[0]]
    assert not bad, "modules sharing a file name (rename one, or list it in PARALLEL_NAMES with a reason):\n" + "\n".join(bad)


@pytest.mark.parametrize("graph, cycle", [({"a": {"b"}, "b": {"a"}}, True), ({"a": {"b"}, "b": set()}, False)])
def test_cycle_finder(graph, cycle):
    # the checks above are only as good as this
    assert (_cycle(graph) is not None) == cycle


def test_nc_plans_and_does_not_read_a_program_back():
    """Issue 44: ``nc`` plans and prints; reading the printed program back (``camcam.post.readback``) and
    measuring it (``camcam.verify``) are the stages after it.  Lazy imports count."""
    bad = [f"{path.relative_to(PACKAGE.parent)}:{line} imports {target}"
           for name, (path, imports) in MODULES.items() if _top(name) == "nc"
           for target, names, line in imports
           if target.startswith(("camcam.verify", "camcam.post.readback"))
           or (target == "camcam.post" and "readback" in names)]
    assert not bad, "\n".join(bad)


def test_no_dialect_names_outside_post():
    """Issue 44: all of a dialect's knowledge (writing, reading back, TCP codes, Klartext) lives in
    ``camcam.post``; no other module names a dialect (the post data files do, they are data)."""
    bad = [f"{path.relative_to(PACKAGE.parent)}:{no}"
           for path in sorted(PACKAGE.rglob("*.py")) if path.relative_to(PACKAGE).parts[0] != "post"
           for no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
           if "heidenhain" in line.lower() or "klartext" in line.lower()]
    assert not bad, "\n".join(bad)


def test_worker_processes_reach_no_stage_below_nc():
    """Issue 44: process plumbing is behind the NC stage.  Stages before ``nc`` neither import
    ``camcam.workers`` nor take a ``workers`` count; the fitter is handed a map-like callable
    (``camcam.toolpath.mapper.Mapper``) instead."""
    bad = []
    for name, (path, imports) in MODULES.items():
        if RANK[_top(name)] >= RANK["nc"] or _top(name) in ("__init__", "workers"):
            continue
        bad += [f"{path.relative_to(PACKAGE.parent)}:{line} imports {target}"
                for target, _, line in imports if target.startswith("camcam.workers")]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                params = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
                bad += [f"{path.relative_to(PACKAGE.parent)}:{node.lineno} {node.name}() takes workers"
                        for a in params if a.arg == "workers"]
    assert not bad, "\n".join(bad)


#: The most positional parameters a public constructor takes (issue 44: a call such as
#: ``RemovalReport(r, s, a, t, ...)`` with 20 values in a row cannot be read or checked by eye).
MAX_POSITIONAL = 4


def _is_dataclass_decorator(node: ast.expr) -> bool:
    target = node.func if isinstance(node, ast.Call) else node
    return (isinstance(target, ast.Name) and target.id == "dataclass") or (
        isinstance(target, ast.Attribute) and target.attr == "dataclass")


def _keyword_true(call: ast.expr, name: str) -> bool:
    return isinstance(call, ast.Call) and any(
        k.arg == name and isinstance(k.value, ast.Constant) and k.value.value is True for k in call.keywords)


def _keyword_false(call: ast.expr, name: str) -> bool:
    return isinstance(call, ast.Call) and any(
        k.arg == name and isinstance(k.value, ast.Constant) and k.value.value is False for k in call.keywords)


def _positional_parameters(cls: ast.ClassDef) -> list[str] | None:
    """The parameters ``cls(...)`` accepts by position, or None when the class is neither a dataclass nor has an
    explicit ``__init__``.  An explicit ``__init__`` wins; a dataclass's fields count up to a ``KW_ONLY`` marker,
    leaving out ``ClassVar``s and ``field(init=False)`` / ``field(kw_only=True)``."""
    init = next((n for n in cls.body
                 if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and n.name == "__init__"), None)
    if init is not None:
        return [a.arg for a in (init.args.posonlyargs + init.args.args)[1:]]
    deco = next((d for d in cls.decorator_list if _is_dataclass_decorator(d)), None)
    if deco is None:
        return None
    if _keyword_true(deco, "kw_only") or _keyword_false(deco, "init"):
        return []
    out = []
    for node in cls.body:
        if not (isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name)):
            continue
        annotation = ast.unparse(node.annotation)
        if "KW_ONLY" in annotation:
            break
        if "ClassVar" in annotation:
            continue
        value = node.value
        if (isinstance(value, ast.Call) and isinstance(value.func, (ast.Name, ast.Attribute))
                and getattr(value.func, "id", getattr(value.func, "attr", None)) == "field"
                and (_keyword_false(value, "init") or _keyword_true(value, "kw_only"))):
            continue
        out.append(node.target.id)
    return out


def _long_positional_constructors(source: str, where: str = "<snippet>") -> list[str]:
    return [f"{where}:{node.lineno} {node.name}({', '.join(params)}): {len(params)} positional"
            for node in ast.walk(ast.parse(source))
            if isinstance(node, ast.ClassDef) and not node.name.startswith("_")
            for params in [_positional_parameters(node)] if params is not None and len(params) > MAX_POSITIONAL]


def test_no_public_constructor_takes_more_than_four_positional_arguments():
    """Issue 44: a call that passes eight values in a row (``MachiningSpec`` took 16, ``RemovalReport`` 20) is
    read by counting, and a field added in the middle shifts every later value without an error.  A public class
    (a dataclass, or one with its own ``__init__``) takes at most four leading values by position — the ones a
    reader expects there, such as ``Feed(x, y, z, feed)`` — and everything else by keyword
    (``@dataclass(kw_only=True)``, ``_: KW_ONLY``, or ``*`` in ``__init__``)."""
    bad = [line for path in sorted(PACKAGE.rglob("*.py"))
           for line in _long_positional_constructors(path.read_text(encoding="utf-8"),
                                                     str(path.relative_to(PACKAGE.parent)))]
    assert not bad, "constructors taking more than 4 positional arguments (make the rest keyword-only):\n" + \
        "\n".join(bad)


def test_the_positional_constructor_check_can_fail():
    # the check above is only as good as this
    snippet = '''
from dataclasses import KW_ONLY, dataclass, field
from typing import ClassVar

@dataclass(frozen=True)
class Five:
    a: int
    b: int
    c: int
    d: int
    e: int = 0

@dataclass(frozen=True, kw_only=True)
class Keywords:
    a: int; b: int; c: int; d: int; e: int

@dataclass
class Marked:
    a: int; b: int; c: int; d: int
    _: KW_ONLY
    e: int

@dataclass
class Excluded:
    a: int; b: int; c: int; d: int
    e: ClassVar[int] = 0
    f: int = field(init=False)
    g: int = field(default=0, kw_only=True)

@dataclass
class _Private:
    a: int; b: int; c: int; d: int; e: int

class Explicit:
    def __init__(self, a, b, c, d, e):
        pass

class Starred:
    def __init__(self, a, b, c, d, *, e):
        pass
'''
    bad = _long_positional_constructors(snippet)
    assert [line.split()[1].split("(")[0] for line in bad] == ["Five", "Explicit"], bad


def test_the_tolerance_keeps_one_name():
    """Issue 44: the tolerance is ``tolerance_mm`` from the spec (``MachiningSpec.tolerance_mm``) to the fitter's
    innermost function; no parameter abbreviates it (``tol`` and ``tol_mm`` were 15 functions of the fitter and
    the roughing).  Library tolerances keep their libraries' names (scipy's ``xtol``, numpy's ``atol``)."""
    bad = []
    for name, (path, _) in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                bad += [f"{path.relative_to(PACKAGE.parent)}:{node.lineno} {node.name}({a.arg})"
                        for a in node.args.posonlyargs + node.args.args + node.args.kwonlyargs
                        if a.arg in ("tol", "tol_mm", "tolerance", "delta", "delta_mm")]
    assert not bad, "\n".join(bad)


def test_no_test_folder_shadows_the_standard_library():
    """A folder of tests/ named like a standard-library module shadows it for every script run from tests/
    (sys.path[0] is the script's folder): tests/inspect/ made numpy's ``import inspect`` load it, and
    tests/make_sample_checksums.py's runs ended in an internal fault (2026-12-07)."""
    import sys

    tests = PACKAGE.parent / "tests"
    bad = sorted(p.name for p in tests.iterdir() if p.is_dir() and p.name in sys.stdlib_module_names)
    bad += sorted(p.stem for p in tests.glob("*.py") if p.stem in sys.stdlib_module_names)
    assert not bad, bad
