"""The trees shipped with aiobt, as package data: ``aiobt.trees`` is this folder.

``nav2/`` holds Nav2's own trees, unmodified (see nav2/NOTICE.md); the build
configuration (pyproject.toml) ships this folder as ``aiobt/trees``, so an
installed aiobt finds them with ``importlib.resources.files("aiobt.trees")``.
"""
