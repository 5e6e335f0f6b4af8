"""``aiobt router`` stopped by SIGTERM at any time after it listens closes its session
and exits 0: peers connect before ``zenoh.open`` returns, so its handlers are set
before the session opens (a SIGTERM then used to kill it: exit -15)."""

from __future__ import annotations

import pytest

from aiobt.testing.bus import start_router

pytestmark = pytest.mark.timeout(120)


def test_a_router_stopped_as_soon_as_it_listens_exits_cleanly() -> None:
    codes = []
    for _ in range(5):
        proc, _where = start_router()
        try:
            codes.append(proc.stop())
        finally:
            proc.cleanup()
    assert codes == [0] * 5
