"""Griffe extension of the famcc API reference (mkdocs.yml, mkdocstrings ``extensions``).

famcc's docstrings are numpydoc read by ``help()`` and by pytest's doctest runner;
two of their habits would render badly as Markdown, so the extension rewrites the
docstring text (never the source) before it is parsed:

1. Doctest blocks outside an ``Examples`` section (module docstrings open with
   one) are fenced as ``pycon`` code; otherwise their output, such as
   ``['last_v', 'z_hat[0]']``, is read as Markdown reference links. ``Examples``
   sections are left alone: the numpy parser already turns their ``>>>`` blocks
   into code.
2. Sphinx roles (``:func:`x```, ``:class:`~a.B```) become inline code.

And the compiled classes are constructed by ``__new__`` (pyo3; ``_core.pyi``), while
the reference shows a class's signature from ``__init__``: a class with a ``__new__``
and no ``__init__`` gets an ``__init__`` with ``__new__``'s parameters, so that its
signature is shown.
"""

from __future__ import annotations

import re
from typing import Any

from griffe import Class, Extension, Function, Inspector, Object, Parameter, Parameters

_ROLE = re.compile(r":(?:py:)?(?:func|class|meth|mod|attr|data|exc|obj|const|term):`~?([^`]+)`")
_UNDERLINE = re.compile(r"^\s*-{3,}\s*$")


def fence_doctests(text: str) -> str:
    lines = text.split("\n")
    out: list[str] = []
    in_examples = False
    fenced = False
    i = 0
    while i < len(lines):
        line = lines[i]
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() and _UNDERLINE.match(nxt):  # a numpydoc section header
            in_examples = line.strip() == "Examples"
        if line.lstrip().startswith(("```", "~~~")):
            fenced = not fenced
        if not fenced and not in_examples and line.lstrip().startswith(">>>"):
            indent = line[: len(line) - len(line.lstrip())]
            block = []
            while i < len(lines) and lines[i].strip():
                block.append(lines[i])
                i += 1
            out += [f"{indent}```pycon", *block, f"{indent}```"]
            continue
        out.append(line)
        i += 1
    return "\n".join(out)


class FamccDocstrings(Extension):
    """Fences stray doctests and turns Sphinx roles into code (see the module)."""

    def on_instance(self, *, obj: Object, **kwargs: Any) -> None:
        doc = obj.docstring
        if doc is None:
            return
        doc.value = _ROLE.sub(r"`\1`", fence_doctests(doc.value))

    def on_class_members(self, *, cls: Class, agent: Any, **kwargs: Any) -> None:
        # Only for source and stubs: the runtime __new__ of a pyo3 class is (*args, **kwargs).
        if not isinstance(agent, Inspector):
            _constructor(cls)


def _constructor(cls: Class) -> None:
    new = cls.members.get("__new__")
    if "__init__" in cls.members or new is None or new.is_alias or not isinstance(new, Function):
        return
    params = [p for i, p in enumerate(new.parameters) if not (i == 0 and p.name == "cls")]
    init = Function(
        "__init__",
        lineno=new.lineno,
        endlineno=new.endlineno,
        parameters=Parameters(Parameter("self"), *params),
        returns="None",
        docstring=new.docstring,
    )
    cls.set_member("__init__", init)
