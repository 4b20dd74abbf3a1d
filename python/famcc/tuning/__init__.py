"""Design and tuning: :func:`design` from requirements (rules, no simulation).

The rules live in the Rust core (``famcc_core::design``; derivation in
``docs/tuning.md``) so that the C ABI and firmware users get the same
numbers; this module translates them and puts them into words.

>>> import famcc
>>> d = famcc.design(2, 1e-3, u_limits=(-12.0, 12.0), eps=0.01, settle_time=2.0,
...                  hold_input=4.0, gain=25.0)
>>> d.ok, d.integral, d.law_order
(True, True, 3)
>>> [f.name for f in d.checks]
['hold-input', 'settle-time', 'sampled-loop']
>>> ctrl = d.controller()
>>> ctrl.order
2
"""

from famcc._common import DesignWarning
from famcc.tuning.assess import Assessment, assess
from famcc.tuning.rules import Design, Finding, Trial, design
from famcc.tuning.search import BUDGETS, FRACTIONS, MU_SAMPLES, tune

__all__ = [
    "BUDGETS",
    "FRACTIONS",
    "MU_SAMPLES",
    "Assessment",
    "Design",
    "DesignWarning",
    "Finding",
    "Trial",
    "assess",
    "design",
    "tune",
]
