"""Test-session set-up: the test extras are required, never silently skipped."""

from __future__ import annotations

import importlib.util

import pytest

#: Modules of the ``test`` extra (pyproject.toml) that tests import.
REQUIRED = ("hypothesis", "mypy", "control", "simple_pid")


def pytest_configure(config: pytest.Config) -> None:
    missing = [m for m in REQUIRED if importlib.util.find_spec(m) is None]
    if missing:
        raise pytest.UsageError(
            f"missing test dependencies: {', '.join(missing)}; install them with "
            "pip install -e '.[test]' (./scripts/test.sh does)"
        )
