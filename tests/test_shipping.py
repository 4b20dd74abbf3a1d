"""What ships: ``famcc --version``, one version everywhere, and the getting-started page's
examples (docs/getting-started.md) run as written."""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from importlib.metadata import version
from pathlib import Path

import famcc
import pytest
from famcc import cli

ROOT = Path(__file__).resolve().parents[1]
GETTING_STARTED = ROOT / "docs" / "getting-started.md"


def test_version_flag_prints_the_version_and_exits_0(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out == f"famcc {famcc.__version__}\n"


def test_version_flag_from_the_console_entry_point() -> None:
    # The interpreter's own module entry, so that this does not depend on PATH.
    out = subprocess.run(
        [sys.executable, "-m", "famcc.cli", "--version"],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    assert re.fullmatch(r"famcc \d+\.\d+\.\d+\S*\n", out.stdout), out.stdout


def test_one_version_everywhere() -> None:
    # The compiled module's version (Cargo), the installed distribution's metadata and
    # pyproject.toml (when the tests run from a source tree) agree.
    assert famcc.__version__ == version("famcc")
    pyproject = ROOT / "pyproject.toml"
    if pyproject.exists():
        declared = tomllib.loads(pyproject.read_text())["project"]["version"]
        assert famcc.__version__ == declared


def _python_blocks(md: str) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", md, flags=re.DOTALL | re.MULTILINE)


@pytest.mark.filterwarnings("error")  # the examples run warning-free, as a reader would want
def test_getting_started_examples_run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    blocks = _python_blocks(GETTING_STARTED.read_text())
    assert len(blocks) >= 3, "docs/getting-started.md lost its examples"
    monkeypatch.chdir(tmp_path)  # examples may write files
    import matplotlib

    matplotlib.use("Agg")
    namespace: dict[str, object] = {"__name__": "getting_started"}
    for i, code in enumerate(blocks):  # one namespace, as a reader pasting them in order
        try:
            code_obj = compile(code, f"{GETTING_STARTED.name}[block {i}]", "exec")
            exec(code_obj, namespace)  # noqa: S102 - the repository's own docs page
        except Exception as exc:  # pragma: no cover - the message names the block
            raise AssertionError(f"getting-started block {i} failed:\n{code}") from exc
