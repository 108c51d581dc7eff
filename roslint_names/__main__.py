"""``python -m roslint_names``: the command line, where no ``roslint-names`` script is on
``PATH`` (a virtual environment not activated, an editor's own interpreter)."""

from __future__ import annotations

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
