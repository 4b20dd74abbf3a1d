"""Figures of closed-loop runs: any run's, the paper's scenarios', the sweep's.

Every function draws on a fresh :class:`matplotlib.figure.Figure` attached to
an Agg canvas, never through ``pyplot``: nothing here touches the global
backend or needs a display, and a figure is freed as soon as it is dropped.

The panels have one home, this module, and two figures use them:

- :func:`figure` (also :meth:`famcc.SimResult.plot`): any run, a user's own
  plant and controller. Panels, chosen by name: ``"error"`` (``z`` and its
  estimate ``z_hat``), ``"accuracy"`` (``z1`` with the eps band and the
  settling time), ``"constraint"`` (the constrained value with its nominal and
  flexible bounds), ``"input"`` (``u``, the limits, saturation and ``-F/G``)
  and ``"xi"`` (the nominal ``xi`` and ``xi~``);
- :func:`scenario_figure` (``famcc reproduce``): the same panels plus the
  paper's extras, in the paper's order: the constrained value zoomed after
  ``T_s``, the phase portrait ``(z1, z2)`` and, at order 3, the constrained
  stage ``(s2, ds2)``.

Axes carry the names and units of the plant's output and input
(:class:`famcc.Signal`), one quantity per line; saturation episodes (commanded
``v`` outside the limits) are shaded; a one-line note at the bottom says the
paper's terms in plain words (docs/glossary.md).

>>> import famcc
>>> from famcc import plot
>>> sc = famcc.scenarios.paper("finite-time")
>>> fig = plot.scenario_figure(sc, sc.run(t_end=1.5))
>>> len(fig.axes), fig.axes[0].get_title()[:9]
(7, '(a) error')
"""

from __future__ import annotations

from famcc.plot.figures import (
    EXTRA_PANELS,
    PANELS,
    figure,
    legend,
    panels_of,
    save,
    scenario_figure,
    scenario_panels,
)
from famcc.plot.sweep import sweep_figure
from famcc.plot.view import constrained_offset

__all__ = [
    "EXTRA_PANELS",
    "PANELS",
    "constrained_offset",
    "figure",
    "legend",
    "panels_of",
    "save",
    "scenario_figure",
    "scenario_panels",
    "sweep_figure",
]
