"""famcc: fully actuated manifold constraint control.

A model-free output-feedback controller (Mu et al.) with a compiled,
allocation-free Rust core. See README.md for a tour.
"""

from famcc._core import __version__

__all__ = ["__version__"]
