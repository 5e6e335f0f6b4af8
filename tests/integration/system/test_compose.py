"""docker-compose.yml cannot rot: its commands are `aiobt up`'s, and they run and navigate.

No Docker here: each service's command runs as a local process against a local
router configured like the compose router (deploy/zenoh-router.json5, user and
password from zenoh.env.example), and a goal is sent through the navigator.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from aiobt.embed import connect
from aiobt.system.catalog import SERVICES
from aiobt.system.commands import service_command
from aiobt.system.config import config_from_dict
from aiobt.testing.bus import ServiceProcess, free_endpoint, port_of, spawn_service, wait_port
from aiobt.transport import BusSettings, BusUnavailable

pytestmark = [pytest.mark.integration]
REPO = Path(__file__).resolve().parents[3]
COMPOSE: dict[str, Any] = yaml.safe_load((REPO / "docker-compose.yml").read_text())
ROUTER_IN_COMPOSE = "tcp/router:7447"


def _env_file() -> dict[str, str]:
    lines = (REPO / "zenoh.env.example").read_text().splitlines()
    pairs = (line.split("=", 1) for line in lines if line and not line.startswith("#"))
    return dict(pair for pair in pairs if len(pair) == 2)


def _services(profile: str | None) -> dict[str, list[str]]:
    return {
        name: spec["command"]
        for name, spec in COMPOSE["services"].items()
        if name != "router" and spec.get("profiles", [None])[0] == profile
    }


@pytest.mark.parametrize("profile", [None, "two-robots"])
def test_every_service_runs_the_command_aiobt_up_runs(profile: str | None) -> None:
    services = _services(profile)
    # every service of the one list (aiobt.system.catalog) on by default, once per robot
    on = sorted(s.name for s in SERVICES if s.enabled)
    assert sorted(command[0] for command in services.values()) == on
    for command in services.values():
        namespace = command[command.index("--namespace") + 1]
        config = config_from_dict(
            {"namespace": namespace, "router": {"listen": ROUTER_IN_COMPOSE}}, "compose"
        )
        assert command == service_command(command[0], config)
    namespaces = {c[c.index("--namespace") + 1] for c in services.values()}
    assert namespaces == ({"robot"} if profile is None else {"robot2"})


@pytest.mark.parametrize("name", [spec.name for spec in SERVICES if not spec.enabled])
def test_a_service_off_by_default_runs_under_its_own_profile(name: str) -> None:
    spec = COMPOSE["services"][name]
    assert spec["profiles"] == [name]
    config = config_from_dict({"router": {"listen": ROUTER_IN_COMPOSE}}, "compose")
    assert spec["command"] == service_command(name, config)


def test_the_router_checks_passwords_and_no_credential_is_baked_in() -> None:
    router = COMPOSE["services"]["router"]
    assert router["image"].startswith("eclipse/zenoh:")
    assert COMPOSE["secrets"]["zenoh_users"] == {"environment": "ZENOH_USERS"}
    config = (REPO / "deploy" / "zenoh-router.json5").read_text()
    assert 'dictionary_file: "/run/secrets/zenoh_users"' in config
    assert "multicast: { enabled: false }" in config
    password = _env_file()["AIOBT_ZENOH_PASSWORD"]
    for baked in ("Dockerfile", "docker-compose.yml", "deploy/zenoh-router.json5"):
        assert password not in (REPO / baked).read_text(), baked
    assert "zenoh.env" in (REPO / ".dockerignore").read_text().split()


@pytest.fixture
def compose_router(tmp_path: Path) -> Iterator[str]:
    """A router with the compose router's config, on a free loopback port."""
    users = tmp_path / "users.txt"
    users.write_text(_env_file()["ZENOH_USERS"] + "\n")
    config = (REPO / "deploy" / "zenoh-router.json5").read_text()
    config = config.replace("/run/secrets/zenoh_users", str(users))
    endpoint = free_endpoint()
    config = re.sub(r'"tcp/0\.0\.0\.0:7447"', json.dumps(endpoint), config)
    path = tmp_path / "router.json5"
    path.write_text(config)
    router = spawn_service(["-m", "aiobt.cli.router", "--config", str(path)])
    try:
        assert wait_port(port_of(endpoint), 20.0), router.output()
        yield endpoint
    finally:
        router.cleanup()


@pytest.mark.timeout(240)
async def test_the_compose_services_run_locally_and_navigate(
    compose_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    credentials = {k: v for k, v in _env_file().items() if k.startswith("AIOBT_")}
    started: list[ServiceProcess] = []
    with contextlib.ExitStack() as cleanup:
        for command in _services(None).values():
            local = [compose_router if arg == ROUTER_IN_COMPOSE else arg for arg in command]
            proc = spawn_service(["-m", "aiobt.cli.main", *local], env=credentials)
            cleanup.callback(proc.cleanup)
            started.append(proc)
        settings = BusSettings(connect=(compose_router,), namespace="robot", connect_timeout=3.0)
        with pytest.raises(BusUnavailable):  # no credentials: the router refuses
            async with connect(settings=settings):
                pass
        for key, value in credentials.items():
            monkeypatch.setenv(key, value)
        try:
            outcome = await _navigate(settings)
            assert outcome.succeeded, outcome
        except BaseException:
            for proc in started:
                print(f"--- {' '.join(proc.args)}\n{proc.output()[-3000:]}")
            raise


async def _navigate(settings: BusSettings) -> Any:
    """One goal, sent once every service is up (as ``aiobt up``'s health: each service's
    liveliness token). Waiting for the navigator alone lost the first goal on a loaded
    machine: the robot (pybullet, the office world) came up later, so the goal found no
    robot pose within the navigator's --pose-timeout and was aborted (TF_ERROR)."""
    async with connect(settings=settings, server_timeout=90.0) as robot:
        for command in _services(None).values():
            name = command[0]
            presence = robot.bus.presence(f"robot/nodes/{name}")
            assert await presence.wait(90.0), f"{name} did not come up"
        async with asyncio.timeout(150.0):
            return await robot.navigate_to(3.0, 9.75, 0.0)  # office: 1 m ahead of the start
