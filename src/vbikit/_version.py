"""The installed package's version (one place; modules import it from here, not from ``vbikit``)."""
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("vbikit")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"
