"""Shared pytest configuration.

aiobt's test plugin (fixtures ``manual_clock``, ``stubs``, ``bt_factory``) is
loaded through its ``pytest11`` entry point (``aiobt.testing.plugin``), the
same way it reaches users' test suites.
"""
