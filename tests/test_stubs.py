"""The type stubs python/famcc/_core.pyi match the compiled module.

- ``mypy.stubtest`` compares every class, method, property and function of the
  stub with ``famcc._core`` at runtime (names, parameter names and kinds,
  defaults, ``@final``, ``__all__``). No allowlist is needed.
- Property annotations are checked against the values the runtime returns.
- mypy type-checks a typed usage snippet (with expected errors marked by
  ``type: ignore`` and ``--warn-unused-ignores``) and the examples, and the
  snippet runs.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import famcc
import numpy as np
import pytest
from famcc import _core

ROOT = Path(__file__).resolve().parents[1]
STUB = Path(famcc.__file__).with_name("_core.pyi")
ALLOWLIST = ROOT / "tests" / "stubtest_allowlist.txt"  # not needed today


def _run(args: list[str], cwd: Path = ROOT) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, PYTHONWARNINGS="ignore", MYPY_FORCE_COLOR="0")
    return subprocess.run(
        args, check=False, cwd=cwd, env=env, capture_output=True, text=True, timeout=300
    )


@pytest.fixture(scope="module", autouse=True)
def stubtest_run():
    """Starts stubtest in the background (it is slow and single-threaded); the
    last test of this module waits for it while mypy runs in the meantime."""
    args = [sys.executable, "-m", "mypy.stubtest", "famcc._core"]
    if ALLOWLIST.is_file():
        args += ["--allowlist", str(ALLOWLIST)]
    env = dict(os.environ, PYTHONWARNINGS="ignore", MYPY_FORCE_COLOR="0")
    proc = subprocess.Popen(
        args, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True
    )
    yield proc
    if proc.poll() is None:
        proc.kill()
        proc.wait()


def test_stub_file_exists_and_package_is_typed():
    assert STUB.is_file()
    assert STUB.with_name("py.typed").is_file()


# -- property annotations vs runtime values -------------------------------------


def _stub_properties() -> dict[str, dict[str, str]]:
    """{class name: {property name: return annotation}} from the stub."""
    tree = ast.parse(STUB.read_text())
    out: dict[str, dict[str, str]] = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            props = {}
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and any(
                    isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list
                ):
                    assert item.returns is not None, f"{node.name}.{item.name} lacks a return type"
                    props[item.name] = ast.unparse(item.returns)
            out[node.name] = props
    return out


_TYPES = {
    "float": (float,),
    "int": (int,),
    "bool": (bool,),
    "str": (str,),
    "_F64Array": (np.ndarray,),
    "tuple[float, float]": (tuple,),
    "tuple[float, ...]": (tuple,),
    "tuple[int, ...]": (tuple,),
    "tuple[float, ...] | None": (tuple, type(None)),
    "float | None": (float, type(None)),
    "ControllerSpec": (_core.ControllerSpec,),
    "Diagnostics": (_core.Diagnostics,),
    "_Transition": (str,),
    "_Discretization": (str,),
    "_DType": (str,),
}


def _instances() -> dict[str, list[object]]:
    ctrl = famcc.Controller(
        2, 1e-3, famcc.FiniteTime(1.0, 0.5), constraint="lateral", eps=0.1, k_u=5.0
    )
    ctrl.step(-1.0)
    gapped = famcc.Controller(2, 1e-3, famcc.Linear(1.0), eps=0.1, k_u=1.0)
    gapped.step(0.5)
    gapped.step(0.5, applied=0.0)
    bank = famcc.ControllerBank(ctrl, 3)
    bank.step(np.zeros(3))
    return {
        "Controller": [
            ctrl,
            famcc.Controller(3, 1e-3, famcc.Linear(2.0), eps=0.5, k_u=1.0, dtype="float32"),
        ],
        "Diagnostics": [ctrl.diagnostics, gapped.diagnostics],
        "ControllerBank": [bank],
        "Linear": [famcc.Linear(2.0)],
        "FiniteTime": [famcc.FiniteTime(1.0, 0.5)],
        "FixedTime": [famcc.FixedTime(1.0, 0.5, 0.5, 2.0)],
        "VariableExponent": [famcc.VariableExponent(1.5, 0.5, 2.0, 3.0)],
        "MoulayDiscontinuous": [famcc.MoulayDiscontinuous(1.0, 1.0, 0.5)],
        "Smooth": [famcc.Smooth(0.15, 0.1)],
        "Nonsingular": [famcc.Nonsingular(0.1, 0.1, 0.1, "sine")],
        "HighGain": [
            famcc.HighGain(0.01, [4.0, 4.0]),
            famcc.HighGain(0.01, [4.0, 4.0], "tustin", [10.0, np.inf]),
        ],
        "Skewed": [famcc.skewed(famcc.FiniteTime(1.0, 0.5), famcc.Nonsingular(0.1, 0.1, 0.1))],
    }


def test_property_annotations_match_runtime_values():
    props = _stub_properties()
    instances = _instances()
    assert set(instances) <= set(props)
    checked = 0
    for cls_name, objs in instances.items():
        for obj in objs:
            assert type(obj).__name__ == cls_name
            for prop, ann in props[cls_name].items():
                assert ann in _TYPES, f"add {ann!r} ({cls_name}.{prop}) to _TYPES"
                value = getattr(obj, prop)
                assert isinstance(value, _TYPES[ann]), (cls_name, prop, ann, value)
                if ann == "_F64Array":
                    assert value.dtype == np.float64 and value.ndim == 1
                if ann.startswith("tuple[float") and value is not None:
                    assert all(isinstance(v, float) for v in value)
                checked += 1
    # Diagnostics alone has 14 properties; every class was covered.
    assert checked > 40
    # Both branches of the optional saturation gap were seen.
    assert instances["Diagnostics"][0].saturation_gap is None
    assert isinstance(instances["Diagnostics"][1].saturation_gap, float)


def test_every_runtime_public_name_is_stubbed():
    tree = ast.parse(STUB.read_text())
    stubbed = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            stubbed.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            stubbed.add(node.target.id)
    assert set(_core.__all__) <= stubbed


# -- mypy on typed usage ---------------------------------------------------------

SNIPPET = """
from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import numpy.typing as npt
from typing_extensions import assert_type

import famcc
from famcc import _core


def build() -> famcc.Controller:
    return famcc.Controller(
        3, 1e-3, [famcc.FixedTime(1.0, 0.5, 0.5, 2.0), famcc.FixedTime(2.0, 0.5, 1.0, 2.0)],
        skew=[famcc.Nonsingular(0.1, 0.1, 0.1), famcc.Nonsingular(3.0, 0.2, 1.0)],
        eps=3.0, k_u=30.0, differentiator=famcc.HighGain.default(3), latch="authors")


ctrl = build()
assert_type(ctrl.step(0.5), float)
assert_type(ctrl.step(0.5, applied=1.0), float)
assert_type(ctrl.step_dt(0.5, 2e-3), float)
assert_type(ctrl.step_state([0.1, 0.0, 0.0]), float)
assert_type(ctrl.step_state(np.zeros(3)), float)
d = ctrl.diagnostics
assert_type(d, famcc.Diagnostics)
assert_type(d.xi, float)
assert_type(d.bounds, tuple[float, float])
assert_type(d.z_hat, npt.NDArray[np.float64])
assert_type(d.clamp_count, int)
assert_type(d.expanded, bool)
assert_type(d.saturation_gap, float | None)
state = ctrl.state()
assert_type(state, npt.NDArray[np.float64])
twin = copy.copy(ctrl)
twin.set_state(state)
assert_type(copy.deepcopy(ctrl), famcc.Controller)
assert_type(pickle.loads(pickle.dumps(ctrl)), Any)
assert_type(ctrl.config(), dict[str, Any])
dtype: str = ctrl.dtype
assert_type(ctrl.order, int)

law = famcc.FiniteTime(k=1.0, p=0.5)
assert_type(law(0.25), float)
assert_type(law(np.linspace(-1.0, 1.0, 5)), npt.NDArray[np.float64])
assert_type(law.slope([0.5, 1.0]), npt.NDArray[np.float64])
assert_type(law.p, float)
h = famcc.skewed(law, famcc.Smooth(eps_s=0.15, eps_z=0.1))
assert_type(h, famcc.Skewed)
assert_type(h(0.3), float)
assert_type(h.inverse(0.3), float)
assert_type(famcc.manifold([1.0, 0.0], famcc.Linear(1.0)), npt.NDArray[np.float64])
assert_type(famcc.transition.S(0.5), float)
assert_type(famcc.transition.U(np.zeros(3), kind="cubic"), npt.NDArray[np.float64])
assert_type(famcc.envelope.rho(2.0, 0.1, 1.0, 0.5), float)
assert_type(famcc.bounds.T_fr([(1.0, 0.5, 0.5, 2.0)]), float)
assert_type(famcc.HighGain(0.01, [4.0, 4.0]).a, tuple[float, ...])

bank = famcc.ControllerBank(ctrl, 4)
assert_type(bank.step(np.zeros(4)), npt.NDArray[np.float64])
assert_type(bank.xi, npt.NDArray[np.float64])
assert_type(len(bank), int)
assert_type(bank.controller(0), famcc.Controller)

try:
    famcc.Linear(-1.0)
except famcc.ConfigError as exc:
    assert isinstance(exc, ValueError)
assert issubclass(_core.StepError, ValueError)


def _never_called() -> None:
    # Each line is an error the stubs must report (--warn-unused-ignores
    # fails if one is no longer reported).
    ctrl.step("0.5")  # type: ignore[arg-type]
    famcc.Controller(2, 1e-3, law, eps=0.1)  # type: ignore[call-arg]
    famcc.Controller(2, 1e-3, law, eps=0.1, k_u=1.0, gain=3.0)  # type: ignore[call-arg]
    famcc.Controller(2, 1e-3, law, eps=0.1, k_u=1.0, constraint="diagonal")  # type: ignore[arg-type]
    famcc.Controller(2, 1e-3, 1.0, eps=0.1, k_u=1.0)  # type: ignore[arg-type]
    famcc.Controller(2, 1e-3, law, famcc.Smooth(0.1, 0.1), eps=0.1, k_u=1.0)  # type: ignore[call-arg]
    law.k = 2.0  # type: ignore[misc]
    d.xi = 0.0  # type: ignore[misc]
    bank.step([0.0, 0.0, 0.0, 0.0])  # type: ignore[arg-type]
    famcc.HighGain(0.01, [4.0, 4.0], discretization="rk4")  # type: ignore[arg-type]


print("typed usage ok")
"""


def _mypy(paths: list[str], *extra: str) -> subprocess.CompletedProcess[str]:
    return _run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--strict",
            "--warn-unused-ignores",
            "--python-version",
            "3.11",
            "--no-error-summary",
            "--show-error-codes",
            *extra,
            *paths,
        ]
    )


def test_typed_usage_type_checks_and_runs(tmp_path):
    snippet = tmp_path / "typed_usage.py"
    snippet.write_text(textwrap.dedent(SNIPPET))
    proc = _mypy([str(snippet)])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    run = _run([sys.executable, str(snippet)], cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "typed usage ok" in run.stdout


def test_examples_type_check():
    examples = [str(ROOT / "examples" / n) for n in ("quickstart.py", "monte_carlo.py")]
    proc = _mypy(examples)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_a_stub_error_is_detected(tmp_path):
    """The check has teeth: a wrong return type in the snippet fails mypy."""
    bad = tmp_path / "bad.py"
    bad.write_text("import famcc\nx: str = famcc.Linear(1.0)(0.5)\n")
    proc = _mypy([str(bad)])
    assert proc.returncode != 0
    assert "assignment" in proc.stdout


def test_stubtest_finds_no_drift(stubtest_run):
    out, _ = stubtest_run.communicate(timeout=300)
    assert stubtest_run.returncode == 0, out
    assert "Success" in out
