"""Input layer: TOML + units -> frozen dataclasses with SI floats."""

from fe_crank.io.engine import load_engine
from fe_crank.io.loadcase import load_loadcase

__all__ = ["load_engine", "load_loadcase"]
