"""roslint-names: a static linter for ROS graph-resource names."""

# Read by hatchling for the package metadata; a literal, because looking the version up
# with importlib.metadata costs 40-70 ms at every start, and pre-commit starts us often.
__version__ = "0.1.0"

PROJECT_URL = "https://github.com/roslint-names/roslint-names"
