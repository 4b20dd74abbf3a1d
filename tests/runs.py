"""Closed-loop runs shared by several test modules, computed once per session."""

from __future__ import annotations

import functools

import famcc


@functools.cache
def scenario_run(name: str, variant: str) -> famcc.SimResult:
    """``famcc.scenarios.paper(name, variant).run()`` at its defaults (1 kHz)."""
    return famcc.scenarios.paper(name, variant).run()
