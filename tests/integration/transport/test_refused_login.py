"""A router with user/password authentication (loopback): a refused login is named as
such, distinct from a missing router, and the router logs it; where it listens is logged."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from aiobt.testing.bus import free_endpoint, running_router
from aiobt.transport import BusSettings, BusUnavailable, _z, open_session

pytestmark = pytest.mark.integration


def credentials(tmp_path: Path, user: str, password: str) -> str:
    path = tmp_path / f"{user}-{password}.json5"
    path.write_text(
        json.dumps({"transport": {"auth": {"usrpwd": {"user": user, "password": password}}}})
    )
    return str(path)


@pytest.mark.timeout(60)
async def test_wrong_password_is_named_and_logged_by_the_router(tmp_path: Path) -> None:
    (tmp_path / "users.txt").write_text("alice:secret\n")
    router_file = tmp_path / "router.json5"
    users = str(tmp_path / "users.txt")
    router_file.write_text(
        json.dumps({"transport": {"auth": {"usrpwd": {"dictionary_file": users}}}})
    )
    with running_router(extra_args=["--config", str(router_file)]) as (router, endpoint):
        assert router.wait_for_output(f"listening on {endpoint}", 10.0), router.output()
        wrong = BusSettings(
            connect=(endpoint,),
            config_file=credentials(tmp_path, "alice", "guess"),
            connect_timeout=0.5,
        )
        with pytest.raises(BusUnavailable) as refused:
            await open_session(wrong)
        message = str(refused.value)
        assert f"the router at {endpoint} refused the session: check user and password" in message
        assert ".rs" not in message
        assert router.wait_for_output("refused a session from 127.0.0.1:", 10.0), router.output()
        assert "wrong password" in router.output()
        good = BusSettings(
            connect=(endpoint,),
            config_file=credentials(tmp_path, "alice", "secret"),
            connect_timeout=5.0,
        )
        session = await open_session(good)
        _z.close(session)
    nobody = free_endpoint()
    with pytest.raises(BusUnavailable) as missing:
        await open_session(BusSettings(connect=(nobody,), connect_timeout=0.3))
    assert f"no router at {nobody}" in str(missing.value)
    assert ".rs" not in str(missing.value)
