"""Test-session set-up: the test extras are required, never silently skipped, and
famcc's own warnings are errors (a test that expects one says so with pytest.warns)."""

from __future__ import annotations

import importlib.util

import pytest

#: Modules of the ``test`` extra (pyproject.toml) that tests import (cosmic_ray: that
#: scripts/mutants-py.sh, which ./scripts/test.sh runs after pytest, imports).
REQUIRED = (
    "hypothesis",
    "mypy",
    "control",
    "simple_pid",
    "pandas",
    "pyarrow",
    "distributed",
    "nbclient",
    "ipykernel",
    "pyadrc",
    "cosmic_ray",
)


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("filterwarnings", "error::famcc.FamccWarning")
    missing = [m for m in REQUIRED if importlib.util.find_spec(m) is None]
    if missing:
        raise pytest.UsageError(
            f"missing test dependencies: {', '.join(missing)}; install them with "
            "pip install -e '.[test,cluster]' (./scripts/test.sh does)"
        )
