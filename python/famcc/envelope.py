"""The prescribed performance function rho (paper eq. rho).

>>> from famcc.envelope import rho
>>> rho(2.0, 0.1, 1.0, 0.0), rho(2.0, 0.1, 1.0, 2.0)
(2.0, 0.1)
"""

from famcc._core import rho

__all__ = ["rho"]
