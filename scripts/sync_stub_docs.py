"""Copies the compiled classes' docstrings into the type stub python/famcc/_core.pyi.

The docstrings of ``famcc._core``'s classes are the binding's doc comments
(crates/famcc-py: the ``///`` comment of each ``#[pyclass]`` and method); the
stub repeats them, so that an editor or a type checker shows the same text.
This script writes into the stub, for every class of the stub, the runtime
docstring of the class and of each of its public methods and properties
(overloaded methods keep none: their overloads are in the stub only).
tests/test_docs.py checks that nothing is left to copy.

    python scripts/sync_stub_docs.py          # rewrite the stub
    python scripts/sync_stub_docs.py --check  # exit 1 when the stub differs
"""

from __future__ import annotations

import ast
import inspect
import sys
from pathlib import Path

STUB = Path(__file__).resolve().parents[1] / "python" / "famcc" / "_core.pyi"


def _is_overload(fn: ast.FunctionDef) -> bool:
    return any(isinstance(d, ast.Name) and d.id == "overload" for d in fn.decorator_list)


def _has_docstring(body: list[ast.stmt]) -> bool:
    first = body[0]
    return (
        isinstance(first, ast.Expr)
        and isinstance(first.value, ast.Constant)
        and isinstance(first.value.value, str)
    )


def runtime_docs(core: object, tree: ast.Module) -> dict[tuple[str, str], str]:
    """{(class, member or ""): cleaned runtime docstring} for the stub's classes."""
    out: dict[tuple[str, str], str] = {}
    for node in tree.body:
        if not isinstance(node, ast.ClassDef) or not hasattr(core, node.name):
            continue
        cls = getattr(core, node.name)
        if cls.__doc__:
            out[(node.name, "")] = inspect.cleandoc(cls.__doc__)
        for item in node.body:
            if not isinstance(item, ast.FunctionDef) or item.name.startswith("_"):
                continue
            if _is_overload(item):
                continue
            member = cls.__dict__.get(item.name)
            if isinstance(member, (staticmethod, classmethod)):
                # pyo3 wraps without copying the function's docstring
                member = member.__func__
            doc = getattr(member, "__doc__", None)
            if doc:
                out[(node.name, item.name)] = inspect.cleandoc(doc)
    return out


def stub_docs(tree: ast.Module) -> dict[tuple[str, str], str]:
    """{(class, member or ""): docstring} as written in the stub."""
    out: dict[tuple[str, str], str] = {}
    for node in tree.body:
        if not isinstance(node, ast.ClassDef):
            continue
        doc = ast.get_docstring(node)
        if doc:
            out[(node.name, "")] = doc
        for item in node.body:
            if isinstance(item, ast.FunctionDef) and not item.name.startswith("_"):
                doc = ast.get_docstring(item)
                if doc:
                    out[(node.name, item.name)] = doc
    return out


def _literal(doc: str, indent: str) -> list[str]:
    prefix = 'r"""' if "\\" in doc else '"""'
    if doc.startswith('"'):
        prefix += " "  # as ruff format writes it (the docstring is the same)
    lines = doc.split("\n")
    if len(lines) == 1:
        return [f'{indent}{prefix}{doc}"""']
    out = [f"{indent}{prefix}{lines[0]}"]
    out += [f"{indent}{line}" if line else "" for line in lines[1:]]
    out.append(f'{indent}"""')
    return out


def rewrite(text: str, docs: dict[tuple[str, str], str]) -> str:
    """The stub ``text`` with the docstrings ``docs``."""
    tree = ast.parse(text)
    lines = text.split("\n")
    # (first line, last line, replacement lines), 0-based, applied bottom-up.
    edits: list[tuple[int, int, list[str]]] = []

    def place(node: ast.ClassDef | ast.FunctionDef, doc: str) -> None:
        first = node.body[0]
        indent = " " * (node.col_offset + 4)
        new = _literal(doc, indent)
        if _has_docstring(node.body):
            edits.append((first.lineno - 1, (first.end_lineno or first.lineno) - 1, new))
        elif isinstance(node, ast.FunctionDef):
            # `def f(...) -> T: ...`: the body becomes the docstring.
            row = first.lineno - 1
            head = lines[row][: first.col_offset].rstrip()
            tail = lines[row][first.end_col_offset :]
            edits.append((row, row, [head, *new[:-1], new[-1] + tail]))
        else:
            row = first.lineno - 1
            edits.append((row, row - 1, [*new, ""]))

    for node in tree.body:
        if not isinstance(node, ast.ClassDef):
            continue
        if (node.name, "") in docs:
            place(node, docs[(node.name, "")])
        for item in node.body:
            if isinstance(item, ast.FunctionDef) and (node.name, item.name) in docs:
                place(item, docs[(node.name, item.name)])
    for start, end, new in sorted(edits, key=lambda e: e[0], reverse=True):
        lines[start : end + 1] = new
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    from famcc import _core

    text = STUB.read_text()
    tree = ast.parse(text)
    wanted = runtime_docs(_core, tree)
    if "--check" in argv:
        differ = sorted(k for k, v in wanted.items() if stub_docs(tree).get(k) != v)
        for cls, member in differ:
            print(f"{STUB.name}: {cls}{'.' + member if member else ''} differs from the runtime")
        return 1 if differ else 0
    new = rewrite(text, wanted)
    if new != text:
        STUB.write_text(new)
        print(f"rewrote {STUB}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
