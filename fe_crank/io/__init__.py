"""Input layer: TOML + units -> frozen dataclasses with SI floats.

The package itself imports nothing: its modules sit in different pipeline layers
(``io.base`` and ``io.units`` at the bottom, ``io.loadcase`` near the top, see
docs/architecture.md), so importing ``fe_crank.io.base`` must not pull in the load-case
reader and, through it, every section parser.  Import the module you need, e.g.
``from fe_crank.io.loadcase import load_loadcase``.
"""
