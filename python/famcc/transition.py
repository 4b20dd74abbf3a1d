"""Smooth transition functions of the paper's Definitions 1-3.

>>> from famcc.transition import T, S, U
>>> T(1.0), S(0.5), U(0.0)
(1.0, 0.5, 0.0)
"""

from famcc._core import transition_s as S
from famcc._core import transition_t as T
from famcc._core import transition_u as U

__all__ = ["S", "T", "U"]
