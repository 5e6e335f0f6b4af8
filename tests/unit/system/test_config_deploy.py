"""One host's share of a deployment in `aiobt up`'s config: the routers it joins, mutual
TLS for its router and services, the access-control rules; and the commands they make."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.system.commands import router_command, service_command
from aiobt.system.config import ConfigError, config_from_dict


@pytest.fixture
def certs(tmp_path: Path) -> str:
    write_certs(tmp_path, CertPlan())
    return str(tmp_path)


def test_the_base_host_s_share(certs: str) -> None:
    config = config_from_dict(
        {
            "safety_chain": False,  # as deploy/base-host.yaml: it runs beside the controller
            "router": {
                "listen": "tls/198.18.0.5:7447",
                "connect": ["tls/198.18.0.6:7447"],
                "certs": certs,
                "host": "base",
                "access_control": "deploy/access-control.json5",
            },
            "services": {"robot": {"enabled": False}, "localization": {"enabled": False},
                         "controller": {"enabled": False}, "behaviors": {"enabled": False}},
        }
    )  # fmt: skip
    assert config.enabled() == ["planner", "navigator"]
    assert router_command(config) == [
        "router", "--listen", "tls/198.18.0.5:7447", "--connect", "tls/198.18.0.6:7447",
        "--config", f"{certs}/router-base.json5",
        "--access-control", "deploy/access-control.json5",
    ]  # fmt: skip
    assert service_command("planner", config) == [
        "planner", "--connect", "tls/198.18.0.5:7447", "--namespace", "robot",
        "--config", f"{certs}/planner.json5",
    ]  # fmt: skip


def test_without_certs_nothing_changes() -> None:
    config = config_from_dict({"router": {"connect": "tcp/10.0.0.2:7447"}})
    assert router_command(config) == [
        "router", "--listen", "tcp/127.0.0.1:7447", "--connect", "tcp/10.0.0.2:7447",
    ]  # fmt: skip
    assert "--config" not in service_command("robot", config)


@pytest.mark.parametrize(
    ("router", "message"),
    [
        ({"connect": [7447]}, "router.connect must be a list of Zenoh endpoints"),
        ({"certs": "/nowhere", "listen": "tls/127.0.0.1:7447"}, "no ca.pem there"),
        ({"certs": "CERTS", "listen": "tcp/127.0.0.1:7447"}, "router.certs needs a tls/"),
        ({"access_control": 3}, "router.access_control must be str"),
    ],
)
def test_bad_deployment_settings_are_named(
    certs: str, router: dict[str, object], message: str
) -> None:
    router = {k: certs if v == "CERTS" else v for k, v in router.items()}
    with pytest.raises(ConfigError, match=message):
        config_from_dict({"router": router}, "host.yaml")
