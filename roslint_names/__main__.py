"""``python -m roslint_names``: the command line, where no ``roslint-names`` script is on
``PATH`` (a virtual environment not activated, an editor's own interpreter)."""

from __future__ import annotations

from .cli import entry

if __name__ == "__main__":
    entry()
