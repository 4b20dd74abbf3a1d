"""The package's layers, read from its source (docs/architecture.md draws them).

Every module of ``python/famcc`` sits in one layer; a module may import only from
its own layer or a lower one, the import graph has no cycle, no module reaches
into ``famcc`` (the top package) for a name another module owns, no hand-written
source file is over 400 lines, and the compiled binding imports no Python module
of the package at run time.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "python" / "famcc"

# Lowest first. A module belongs to the first entry that is it or a package above it.
LAYERS: list[tuple[str, ...]] = [
    ("famcc._core",),
    ("famcc._common", "famcc.progress", "famcc.bounds", "famcc.envelope", "famcc.transition"),
    ("famcc.signals", "famcc.plants", "famcc.families", "famcc.plant_suite"),
    (
        "famcc.sim",
        "famcc.simulation",
        "famcc.joints",
        "famcc.metrics",
        "famcc.summary",
        "famcc.verdicts",
        "famcc.plot",
    ),
    ("famcc.tuning", "famcc.scenarios"),
    (
        "famcc.campaigns",
        "famcc.sweep",
        "famcc.compare",
        "famcc.peers",
        "famcc.interop",
        "famcc.reporting",
    ),
    ("famcc.cli", "famcc"),
]


def module_name(path: Path) -> str:
    rel = path.relative_to(PKG.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def layer_of(mod: str) -> int:
    best, best_len = -1, -1
    for i, names in enumerate(LAYERS):
        for name in names:
            if (mod == name or mod.startswith(name + ".")) and len(name) > best_len:
                best, best_len = i, len(name)
    if best < 0:
        raise AssertionError(f"{mod} is in no layer: add it to LAYERS and docs/architecture.md")
    return best


def sources() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PKG.rglob("*.py"))}


def _run_time_nodes(tree: ast.AST) -> list[ast.AST]:
    """Every node but those under ``if TYPE_CHECKING:`` (annotations only, never run)."""
    out: list[ast.AST] = []
    todo = [tree]
    while todo:
        node = todo.pop()
        out.append(node)
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                todo.extend(child.orelse)
                continue
            todo.append(child)
    return out


def imports_of(mod: str, path: Path, known: set[str]) -> set[str]:
    """The package modules ``mod`` imports at run time, function-local imports included."""
    tree = ast.parse(path.read_text(), filename=str(path))
    is_pkg = path.name == "__init__.py"
    out: set[str] = set()
    for node in _run_time_nodes(tree):
        targets: list[str] = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = mod.split(".")
                drop = node.level - 1 if is_pkg else node.level
                anchor = anchor[: len(anchor) - drop]
                base = ".".join(anchor + ([base] if base else []))
            for a in node.names:
                sub = f"{base}.{a.name}"
                targets.append(sub if sub in known else base)
        for t in targets:
            if t == "famcc._core" or t.startswith("famcc._core."):
                out.add("famcc._core")
            elif t in known:
                out.add(t)
    out.discard(mod)
    return out


def graph() -> dict[str, set[str]]:
    src = sources()
    known = set(src) | {"famcc._core"}
    return {m: imports_of(m, p, known) for m, p in src.items()}


def test_every_module_has_a_layer() -> None:
    for mod in sources():
        layer_of(mod)


def test_no_import_from_a_lower_layer_into_a_higher_one() -> None:
    bad = [
        f"{m} (layer {layer_of(m)}) imports {t} (layer {layer_of(t)})"
        for m, targets in graph().items()
        for t in sorted(targets)
        if layer_of(t) > layer_of(m)
    ]
    assert not bad, "\n".join(bad)


def test_no_submodule_reaches_into_the_top_package() -> None:
    bad = [
        m
        for m, targets in graph().items()
        if m not in {"famcc", "famcc.cli"} and "famcc" in targets
    ]
    assert not bad, f"these import famcc itself; import the owning module instead: {bad}"


def find_cycle(g: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n: str) -> list[str] | None:
        state[n] = 1
        stack.append(n)
        for t in sorted(g.get(n, ())):
            if state.get(t) == 1:
                return [*stack[stack.index(t) :], t]
            if t not in state and (c := visit(t)):
                return c
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(g):
        if n not in state and (c := visit(n)):
            return c
    return None


def test_no_import_cycle() -> None:
    # A package's __init__ re-exporting its children is not a cycle of the design,
    # so edges from a package to its own submodules are left out.
    g = {m: {t for t in ts if not t.startswith(m + ".")} for m, ts in graph().items()}
    cycle = find_cycle(g)
    assert cycle is None, " -> ".join(cycle or [])


def test_the_cycle_finder_finds_a_cycle() -> None:
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


@pytest.mark.parametrize(
    "tree", ["python/famcc", "crates/famcc-py/src", "crates/famcc-sim/src", "scripts"]
)
def test_no_source_file_is_over_400_lines(tree: str) -> None:
    long = {
        str(p.relative_to(ROOT)): n
        for p in sorted((ROOT / tree).rglob("*"))
        if p.suffix in {".py", ".rs", ".pyi"}
        and p.name != "_core.pyi"  # generated by the binding (scripts/sync_stub_docs.py)
        and (n := len(p.read_text().splitlines())) > 400
    }
    assert not long, long


def test_the_binding_imports_no_python_module_of_the_package() -> None:
    pattern = re.compile(r"""import\(\s*(?:py\s*,\s*)?c?"famcc(?!\._core")""")
    hits = [
        str(p.relative_to(ROOT))
        for p in sorted((ROOT / "crates" / "famcc-py" / "src").rglob("*.rs"))
        if pattern.search(p.read_text())
    ]
    assert not hits, hits


#: Why a function may import from the package: a heavy optional dependency loads only
#: when used. Every function-local package import outside the CLI says which, on its line.
DEFERRED = re.compile(r"#\s*deferred:.*\b(matplotlib|pandas|pyarrow|dask|mujoco)\b")
MAX_DEFERRED = 6


def function_local_imports(path: Path) -> list[tuple[int, str]]:
    """``(line, source line)`` of every package import inside a function of ``path``."""
    text = path.read_text()
    lines = text.splitlines()
    out = []
    for fn in ast.walk(ast.parse(text, filename=str(path))):
        if not isinstance(fn, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        for node in ast.walk(fn):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom) and not node.level
                else []
            )
            relative = isinstance(node, ast.ImportFrom) and node.level > 0
            if relative or any(n == "famcc" or n.startswith("famcc.") for n in names):
                out.append((node.lineno, lines[node.lineno - 1]))
    return sorted(set(out))


def test_function_local_package_imports_are_few_and_say_why() -> None:
    found = [
        (str(p.relative_to(ROOT)), n, line.strip())
        for p in sorted(PKG.rglob("*.py"))
        if p.name != "cli.py"  # each subcommand imports what it runs
        for n, line in function_local_imports(p)
    ]
    unexplained = [f"{f}:{n}: {line}" for f, n, line in found if not DEFERRED.search(line)]
    assert not unexplained, "import these at the top of the file:\n" + "\n".join(unexplained)
    assert len(found) <= MAX_DEFERRED, found


def test_the_walk_sees_a_function_level_upward_import_and_circle(tmp_path: Path) -> None:
    known = {"famcc.sim", "famcc.tuning", "famcc.cli"}
    sim = tmp_path / "sim.py"
    sim.write_text(
        "import numpy as np\n\n"
        "def run():\n"
        "    from famcc.tuning import tune  # an upward import, in a function\n"
        "    if True:\n"
        "        from famcc import cli\n"
        "    return tune\n"
    )
    tuning = tmp_path / "tuning.py"
    tuning.write_text("from famcc.sim import run\n")
    g = {"famcc.sim": imports_of("famcc.sim", sim, known)}
    g["famcc.tuning"] = imports_of("famcc.tuning", tuning, known)
    assert g["famcc.sim"] == {"famcc.tuning", "famcc.cli"}
    assert [f"{m} -> {t}" for m in g for t in sorted(g[m]) if layer_of(t) > layer_of(m)] == [
        "famcc.sim -> famcc.cli",
        "famcc.sim -> famcc.tuning",
    ]
    assert find_cycle(g) == ["famcc.sim", "famcc.tuning", "famcc.sim"]
    lines = [line for _, line in function_local_imports(sim)]
    assert len(lines) == 2 and not any(DEFERRED.search(x) for x in lines)
    sim.write_text("def draw():\n    from famcc import plot  # deferred: matplotlib\n")
    assert all(DEFERRED.search(x) for _, x in function_local_imports(sim))
    sim.write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from famcc.tuning import Design  # annotations only: no edge\n"
    )
    assert imports_of("famcc.sim", sim, known) == set()
