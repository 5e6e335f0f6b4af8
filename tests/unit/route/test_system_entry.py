"""The route server in ``aiobt up`` (off by default, as in Nav2) and docker-compose."""

from __future__ import annotations

from pathlib import Path

from aiobt.cli.main import COMMANDS
from aiobt.system.commands import available, service_command
from aiobt.system.config import config_from_dict
from aiobt_services.route.graphs import OFFICE, graph_path

REPO = Path(__file__).resolve().parents[3]


def test_off_by_default_and_on_when_enabled() -> None:
    assert "route" not in config_from_dict({}).enabled()
    config = config_from_dict({"services": {"route": {"enabled": True}}, "speed": 5.0})
    assert config.enabled()[-1] == "route"
    assert available("route")
    assert COMMANDS["route"][0] == "aiobt_services.route.main"
    command = service_command("route", config)
    assert command[:5] == ["route", "--connect", "tcp/127.0.0.1:7447", "--namespace", "robot"]
    assert command[5:] == ["--graph-filepath", "office", "--sim-time"]


def test_the_world_names_its_graph() -> None:
    assert graph_path("office") == OFFICE
    assert graph_path("/maps/warehouse.yaml") == Path("/maps/warehouse.geojson")
    assert graph_path("/maps/lanes.geojson") == Path("/maps/lanes.geojson")
