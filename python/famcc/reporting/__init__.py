"""Reports of closed-loop runs: ``famcc.report`` for any runs, ``famcc reproduce``.

:func:`report` writes a markdown report with figures for any list of runs (a
user's own plants and controllers): a results table, the claims judged against
the requirements the user gives (none otherwise), notes in plain words and one
figure per run (:func:`famcc.plot.figure`). :func:`reproduce` runs the paper's
scenarios of :mod:`famcc.scenarios` and writes its report through the same
writer, with the paper's columns, claims (:meth:`famcc.scenarios.Scenario.verdicts`),
notes and figures (:func:`famcc.plot.scenario_figure`). Both write ``report.md``,
``summary.json`` (the same numbers) and one PNG per run. The numbers come from
:class:`famcc.SimResult`'s metrics and :mod:`famcc.verdicts`; nothing is tuned
or re-derived here.

The module is ``famcc.reporting``; ``famcc.report`` and ``famcc.reproduce`` are
its two entry points.

>>> import tempfile, famcc
>>> from famcc import reporting
>>> with tempfile.TemporaryDirectory() as d:
...     recs = reporting.reproduce(d, names=["finite-time"], t_end=4.0, figures=False,
...                                progress=None)
>>> [(v["name"], v["status"]) for v in recs[0]["verdicts"]]
[('settling', 'held'), ('unsaturated', 'held'), ('nominal', 'held')]
>>> recs[0]["settling_time"] < 3.0
True
"""

from __future__ import annotations

from famcc.progress import Progress
from famcc.reporting.paper import VARIANT_DIFFERENCES as VARIANT_DIFFERENCES
from famcc.reporting.paper import reproduce, write_report
from famcc.reporting.records import diverged as diverged
from famcc.reporting.records import measure, run_record
from famcc.reporting.runs import report
from famcc.reporting.tables import headline

__all__ = ["Progress", "headline", "measure", "report", "reproduce", "run_record", "write_report"]
