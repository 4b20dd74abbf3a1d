"""The compiled classes document themselves (issue 16): ``help(famcc.Controller)``
and every public class of ``famcc._core`` show a numpydoc docstring with every
constructor parameter, its type, unit and default, and a runnable example, and
their signatures show the real defaults.

- ``inspect.signature`` of every class and public method has no ``...`` default.
- The ``Parameters`` section names every parameter of the signature, in order,
  and writes each default as the signature has it (``, default 1.0``).
- The defaults the signatures show are the ones in effect: famcc-core's, which
  the binding passes when an argument is omitted (a pyo3 signature shows only
  literal defaults, so the binding spells them out in its ``text_signature``;
  this checks that they cannot drift).
- The docstrings' examples run (pytest's doctest collection reads Python modules
  only, so the extension's are run here).
- The stub's docstrings are the runtime's (``scripts/sync_stub_docs.py`` copies them).
"""

from __future__ import annotations

import ast
import doctest
import importlib.util
import inspect
import pydoc
import re
import warnings
from pathlib import Path
from typing import Any

import famcc
import numpy as np
import pytest
from famcc import _core

ROOT = Path(__file__).resolve().parents[1]

# The classes with a constructor, and those built by famcc only.
CONSTRUCTIBLE = [
    "Controller",
    "ControllerBank",
    "HighGain",
    "Observer",
    "Linear",
    "FiniteTime",
    "FixedTime",
    "VariableExponent",
    "MoulayDiscontinuous",
    "Smooth",
    "Nonsingular",
    "PaperPlant",
]
NOT_CONSTRUCTIBLE = ["Diagnostics", "Skewed"]
CLASSES = CONSTRUCTIBLE + NOT_CONSTRUCTIBLE


def _public_methods(cls: type) -> dict[str, Any]:
    """The public methods defined by the class itself (``__call__`` is a slot of
    pyo3's, whose docstring is Python's generic one: the class documents it)."""
    out = {}
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if callable(member) or isinstance(member, staticmethod):
            out[name] = getattr(cls, name)
    return out


_HEADER = re.compile(r"^(\S[^\n]*)\n-{3,}$", re.MULTILINE)


def _sections(doc: str) -> dict[str, str]:
    """{numpydoc section title: its text} of a docstring."""
    doc = inspect.cleandoc(doc)
    heads = list(_HEADER.finditer(doc))
    out = {"": doc[: heads[0].start()] if heads else doc}
    for i, m in enumerate(heads):
        end = heads[i + 1].start() if i + 1 < len(heads) else len(doc)
        out[m.group(1).strip()] = doc[m.end() : end]
    return out


def _parameters(doc: str) -> list[tuple[str, str]]:
    """[(name, type line)] of the ``Parameters`` section."""
    text = _sections(doc).get("Parameters", "")
    out = []
    for line in text.split("\n"):
        if line and not line[0].isspace():
            name, _, kind = line.partition(" : ")
            out.append((name.strip(), kind.strip()))
    return out


def _signature_parameters(obj: Any) -> list[inspect.Parameter]:
    sig = inspect.signature(obj)
    return [p for p in sig.parameters.values() if p.name not in ("self", "cls")]


def test_the_list_covers_every_public_class():
    exported = {
        name
        for name in famcc.__all__
        if isinstance(getattr(famcc, name), type)
        and getattr(famcc, name).__module__ == "famcc._core"
        and not issubclass(getattr(famcc, name), BaseException)
    }
    assert exported <= set(CLASSES)
    in_core = {n for n in _core.__all__ if isinstance(getattr(_core, n), type)}
    assert set(CLASSES) <= in_core


@pytest.mark.parametrize("name", CONSTRUCTIBLE)
def test_signatures_show_real_defaults(name):
    cls = getattr(_core, name)
    params = _signature_parameters(cls)
    assert params, name
    for p in params:
        assert p.default is not Ellipsis, f"{name}({p.name}=...)"
    for meth, fn in _public_methods(cls).items():
        for p in _signature_parameters(fn):
            assert p.default is not Ellipsis, f"{name}.{meth}({p.name}=...)"


def test_controller_signature():
    sig = inspect.signature(famcc.Controller)
    defaults = {p.name: p.default for p in sig.parameters.values()}
    assert defaults["constraint"] == "longitudinal"
    assert defaults["settle_time"] == 1.0 and defaults["k0"] == 2.0
    assert defaults["gamma"] == "log" and defaults["latch"] == "paper"
    assert defaults["rho_e"] == "auto" and defaults["differentiator"] == "auto"
    assert defaults["transition"] == "exponential" and defaults["dtype"] == "float64"
    kinds = {p.name: p.kind for p in sig.parameters.values()}
    assert kinds["dt"] is inspect.Parameter.POSITIONAL_OR_KEYWORD
    assert kinds["eps"] is inspect.Parameter.KEYWORD_ONLY
    assert sig.parameters["eps"].default is inspect.Parameter.empty
    assert sig.parameters["k_u"].default is inspect.Parameter.empty


def test_help_shows_the_documentation():
    text = pydoc.render_doc(famcc.Controller, renderer=pydoc.plaintext)
    assert "see `famcc.Controller` for the documentation" not in text
    assert "settle_time=1.0" in text and "Ellipsis" not in text
    for section in ("Parameters", "Raises", "Warns", "Notes", "Examples"):
        assert section in text


def _documented_default(kind: str) -> str | None:
    m = re.search(r", default (.+)$", kind)
    return m.group(1) if m else None


@pytest.mark.parametrize("name", CONSTRUCTIBLE)
def test_parameters_section_names_every_parameter(name):
    cls = getattr(_core, name)
    documented = _parameters(cls.__doc__)
    params = _signature_parameters(cls)
    assert [n for n, _ in documented] == [p.name for p in params]
    for (_, kind), p in zip(documented, params, strict=True):
        assert kind, f"{name}: {p.name} has no type"
        want = None if p.default is inspect.Parameter.empty else repr(p.default)
        assert _documented_default(kind) == want, (name, p.name, kind)


@pytest.mark.parametrize("name", CLASSES)
def test_methods_document_their_parameters(name):
    cls = getattr(_core, name)
    for meth, fn in _public_methods(cls).items():
        assert fn.__doc__, f"{name}.{meth} has no docstring"
        params = _signature_parameters(fn)
        if not params:
            continue
        documented = _parameters(fn.__doc__)
        # numpydoc spells a catch-all with its stars (``**overrides``).
        stars = {inspect.Parameter.VAR_POSITIONAL: "*", inspect.Parameter.VAR_KEYWORD: "**"}
        want_names = [stars.get(p.kind, "") + p.name for p in params]
        assert [n for n, _ in documented] == want_names, f"{name}.{meth}"
        for (_, kind), p in zip(documented, params, strict=True):
            want = None if p.default is inspect.Parameter.empty else repr(p.default)
            assert _documented_default(kind) == want, (name, meth, p.name, kind)
        if meth not in ("reset", "set_state"):  # these return None
            assert "Returns" in _sections(fn.__doc__), f"{name}.{meth}"


@pytest.mark.parametrize("name", CLASSES)
def test_docstrings_have_summary_and_examples(name):
    cls = getattr(_core, name)
    sections = _sections(cls.__doc__)
    assert sections[""].strip(), name
    assert ">>>" in sections.get("Examples", ""), f"{name} has no example"


@pytest.mark.parametrize("name", CLASSES)
def test_examples_run(name):
    cls = getattr(_core, name)
    docs = {name: cls.__doc__}
    for meth, fn in _public_methods(cls).items():
        docs[f"{name}.{meth}"] = fn.__doc__ or ""
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    ran = 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the examples are free of warnings
        for qualname, doc in docs.items():
            test = parser.get_doctest(doc, {}, f"famcc._core.{qualname}", None, 0)
            ran += len(test.examples)
            runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{name}: {result.failed} example(s) failed"
    assert ran > 0


# -- the defaults shown are the ones in effect ------------------------------------


def _defaults(obj: Any) -> dict[str, Any]:
    return {
        p.name: p.default
        for p in _signature_parameters(obj)
        if p.default is not inspect.Parameter.empty
    }


_CONTROLLERS = [
    # order 2, LaMC: the paper's example 1
    {
        "order": 2,
        "dt": 1e-3,
        "feedback": famcc.FiniteTime(1.0, 0.5),
        "constraint": "lateral",
        "eps": 0.1,
    },
    # order 4, LoMC: the "auto" differentiator is the Tustin one
    {"order": 4, "dt": 1e-3, "feedback": famcc.Linear(2.0), "eps": 0.5},
    # order 1: no stages, no differentiator
    {"order": 1, "dt": 1e-3, "eps": 0.05},
]


@pytest.mark.parametrize("base", _CONTROLLERS, ids=["order2", "order4", "order1"])
def test_controller_defaults_are_in_effect(base):
    base = dict(base, k_u=5.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # DesignWarnings of the order-4 case
        omitted = famcc.Controller(**base)
        for name, default in _defaults(famcc.Controller).items():
            if name in base:
                continue
            given = famcc.Controller(**base, **{name: default})
            assert given.config() == omitted.config(), name
            assert repr(given) == repr(omitted), name
    config = omitted.config()
    sig = _defaults(famcc.Controller)
    for key in ("settle_time", "k0", "gamma", "latch", "transition"):
        assert config[key] == sig[key], key
    if "constraint" not in base:
        assert config["constraint"] == sig["constraint"]
    assert omitted.dtype == sig["dtype"]


def test_other_defaults_are_in_effect():
    h = famcc.HighGain(0.01, [4.0, 6.0, 4.0])
    assert h == famcc.HighGain(0.01, [4.0, 6.0, 4.0], **_defaults(famcc.HighGain))
    assert h.discretization == _defaults(famcc.HighGain)["discretization"]
    d = _defaults(famcc.HighGain.default)
    assert famcc.HighGain.default(3) == famcc.HighGain.default(3, **d) == h
    for cls, args in ((famcc.Smooth, (0.15, 0.1)), (famcc.Nonsingular, (0.1, 0.1, 0.1))):
        obj = cls(*args)
        assert obj == cls(*args, **_defaults(cls))
        assert obj.transition == _defaults(cls)["transition"]
    plant = _core.PaperPlant(2, "paper")
    again = _core.PaperPlant(2, "paper", **_defaults(_core.PaperPlant))
    x = [0.3, -0.2]
    assert plant.x0 == again.x0 and plant.rhs(0.5, x, 1.0) == again.rhs(0.5, x, 1.0)
    bank = famcc.ControllerBank(famcc.Controller(1, 1e-3, eps=0.05, k_u=1.0), 3)
    with pytest.raises(famcc.StepError):  # the default is "raise"
        bank.step(np.array([0.1, np.nan, 0.3]), **_defaults(famcc.ControllerBank.step))


# -- the stub says the same --------------------------------------------------------


def _sync_module() -> Any:
    spec = importlib.util.spec_from_file_location(
        "sync_stub_docs", ROOT / "scripts" / "sync_stub_docs.py"
    )
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_stub_docstrings_are_the_runtime_ones():
    sync = _sync_module()
    tree = ast.parse(sync.STUB.read_text())
    runtime = sync.runtime_docs(_core, tree)
    stub = sync.stub_docs(tree)
    for name in CLASSES:
        assert (name, "") in runtime, name
    differ = sorted(k for k in runtime.keys() | stub.keys() if runtime.get(k) != stub.get(k))
    assert not differ, f"run python scripts/sync_stub_docs.py: {differ}"


def test_sync_rewrites_a_stale_docstring():
    """The sync script puts the runtime docstrings in place, and the synced stub
    is a fixed point."""
    sync = _sync_module()
    text = sync.STUB.read_text()
    docs = sync.runtime_docs(_core, ast.parse(text))
    assert sync.rewrite(text, docs) == text
    stale = 'class Controller:\n    """Old."""\n\n    def lint(self) -> list[str]: ...\n'
    fixed = sync.stub_docs(ast.parse(sync.rewrite(stale, docs)))
    assert fixed[("Controller", "")] == docs[("Controller", "")]
    assert fixed[("Controller", "lint")] == docs[("Controller", "lint")]
