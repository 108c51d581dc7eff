"""What changes the user's files, beside the pipeline that only reads them.

``--fix`` and ``--diff`` (``fixing``), RN203's workspace-wide renames (``renames``),
``--add-noqa`` (``noqa``), ``--baseline``/``--write-baseline`` (``baseline``) and the
``--changed-since`` gate (``changes``). Every byte any of them writes, and every report
written with ``--output``, goes through ``files``: atomic, only onto the bytes an edit
was computed from, all files of one change or none.
"""
