"""roslint-names: a static linter for ROS graph-resource names."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("roslint-names")
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0.0.0+source"

PROJECT_URL = "https://github.com/roslint-names/roslint-names"
