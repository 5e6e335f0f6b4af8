"""The docking server in ``aiobt up`` (off by default, as in Nav2) and docker-compose."""

from __future__ import annotations

from pathlib import Path

from aiobt.cli.main import COMMANDS
from aiobt.system.commands import available, service_command
from aiobt.system.config import config_from_dict
from aiobt_services.docking.database import DATABASES_DIR, database_path

REPO = Path(__file__).resolve().parents[3]


def test_off_by_default_and_on_when_enabled() -> None:
    assert "docking" not in config_from_dict({}).enabled()
    config = config_from_dict({"services": {"docking": {"enabled": True}}, "speed": 5.0})
    assert config.enabled()[-1] == "docking"
    assert available("docking")
    assert COMMANDS["docking"][0] == "aiobt_services.docking.main"
    command = service_command("docking", config)
    assert command[5:] == ["--dock-database", "office", "--sim-time"]


def test_a_shipped_world_names_its_database() -> None:
    assert database_path("office") == DATABASES_DIR / "office.yaml"
    assert database_path("small") == DATABASES_DIR / "small.yaml"
    assert database_path("/maps/docks.yaml") == Path("/maps/docks.yaml")
