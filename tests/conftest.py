"""Test-session set-up: the test extra is required, the optional groups are marked, and
famcc's own warnings are errors (a test that expects one says so with pytest.warns).

pytest runs with only the ``test`` extra installed. A test that needs more is marked with its
group (pyproject.toml registers the markers); when the group's modules are missing it is
skipped with a reason that names the extra to install, and the summary lists it (``-rs`` in
pyproject.toml's addopts): never a silent skip. ``--require-extra GROUP`` makes a missing
group an error instead (the python session of the test command passes ``cluster``: it
installs that extra, so its tests must run).
"""

from __future__ import annotations

import importlib.util

import pytest

#: Modules of the ``test`` extra (pyproject.toml) that tests import.
REQUIRED = (
    "hypothesis",
    "mypy",
    "control",
    "simple_pid",
    "pandas",
    "pyarrow",
    "nbclient",
    "ipykernel",
    "pyadrc",
)

#: Marker -> (the extra that provides it, the modules its tests import).
GROUPS = {
    "cluster": ("cluster", ("dask", "distributed")),
    "mutation": ("mutation", ("cosmic_ray",)),
}


def _missing(modules: tuple[str, ...]) -> list[str]:
    return [m for m in modules if importlib.util.find_spec(m) is None]


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--require-extra",
        action="append",
        default=[],
        choices=sorted(GROUPS),
        help="fail, instead of skipping its tests, when this marked group's extra is missing",
    )


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("filterwarnings", "error::famcc.FamccWarning")
    missing = _missing(REQUIRED)
    if missing:
        raise pytest.UsageError(
            f"missing test dependencies: {', '.join(missing)}; install them with "
            "pip install -e '.[test]' (./scripts/test.sh does)"
        )
    for group in config.getoption("--require-extra"):
        extra, modules = GROUPS[group]
        if missing := _missing(modules):
            raise pytest.UsageError(
                f"--require-extra {group}: {', '.join(missing)} missing; "
                f"pip install -e '.[test,{extra}]'"
            )


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for group, (extra, modules) in GROUPS.items():
        if not (missing := _missing(modules)):
            continue
        skip = pytest.mark.skip(
            reason=f"marked {group}: needs the {extra} extra ({', '.join(missing)} missing): "
            f"pip install -e '.[test,{extra}]'"
        )
        for item in items:
            if item.get_closest_marker(group) is not None:
                item.add_marker(skip)
