"""moorline: nonlinear statics and dynamics of ocean cables and the bodies they hold."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("moorline")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+local"

__all__ = ["__version__"]
