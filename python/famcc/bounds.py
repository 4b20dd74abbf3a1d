"""Settling-time bounds of the paper's corollaries, in seconds.

The time for |z1| to reach the preset accuracy is below ``settle_time`` plus
these values (after saturation: ``max(T_e, settle_time)`` plus them).

>>> from famcc import bounds
>>> bounds.finite_time(1.0, 0.5, -1.0)           # T_fn', example 1
2.0
>>> round(bounds.variable_exponent(1.5, 0.5, 2.0, 3.0), 2)   # T_fxe', example 2
3.32
>>> bounds.fixed_time([(1.0, 0.5, 0.5, 2.0), (2.0, 0.5, 1.0, 2.0)])  # T_fr', example 3
6.0
"""

from famcc._core import finite_time, fixed_time, variable_exponent

#: Aliases with the paper's names.
T_fn = finite_time
T_fxe = variable_exponent
T_fr = fixed_time

__all__ = ["T_fn", "T_fr", "T_fxe", "finite_time", "fixed_time", "variable_exponent"]
