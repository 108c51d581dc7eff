"""What the user can mend: the error every problem with the user's arguments, settings or
files is raised as (a bad config key, an unreadable path, a baseline of another format),
which the CLI reports as such, its message alone with exit 2, never as an internal error.
It lives apart from the modules that raise it: the CLI catches it whatever the run
imported (a re-run of unchanged files imports none of the editing modules)."""

from __future__ import annotations


class UserError(Exception):
    """A problem with the user's arguments, settings or files, said in its message."""
