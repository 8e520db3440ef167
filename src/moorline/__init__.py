"""moorline: nonlinear statics and dynamics of ocean cables and the bodies they hold."""

__version__ = "0.1.0"
"""The package version (the single source: ``pyproject.toml`` reads it from here, so the
command line does not pay for ``importlib.metadata`` at start-up)."""

__all__ = ["__version__"]
