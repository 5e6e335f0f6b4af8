"""Shared pytest configuration: aiobt's test plugin (manual_clock, stubs, bt_factory).

The plugin should also be published as a ``pytest11`` entry point
(``aiobt = "aiobt.testing.plugin"``) once pyproject.toml lists it.
"""

pytest_plugins = ["aiobt.testing.plugin"]
