"""``endpoint``: up's test fixture (a free loopback endpoint; what still mentions it is
killed at the end), shared with tests/integration/system/test_up.py."""

from ..system.test_up import endpoint

__all__ = ["endpoint"]
