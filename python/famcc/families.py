"""Deprecated home of the plant families: use :mod:`famcc.plants` (``famcc.plants.family``).

Kept so that existing imports work; every name is :mod:`famcc.plants`'.
"""

from famcc.plants.catalog import FAMILIES, family, names
from famcc.plants.family import Family, FamilyPlant

__all__ = ["FAMILIES", "Family", "FamilyPlant", "family", "names"]
