"""The following server in ``aiobt up`` (off by default, as in Nav2) and docker-compose."""

from __future__ import annotations

from pathlib import Path

from aiobt.cli.main import COMMANDS
from aiobt.system.commands import available, service_command
from aiobt.system.config import config_from_dict

REPO = Path(__file__).resolve().parents[3]


def test_off_by_default_and_on_when_enabled() -> None:
    assert "following" not in config_from_dict({}).enabled()
    config = config_from_dict({"services": {"following": {"enabled": True}}, "speed": 5.0})
    assert "following" in config.enabled()
    assert available("following")
    assert COMMANDS["following"][0] == "aiobt_services.following.main"
    command = service_command("following", config)
    assert command == ["following", "--connect", "tcp/127.0.0.1:7447", "--namespace", "robot",
                       "--sim-time"]  # fmt: skip
