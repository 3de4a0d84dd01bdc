"""The package version (one place; ``fe_crank.__version__`` re-exports it)."""

__version__ = "0.1.0"
