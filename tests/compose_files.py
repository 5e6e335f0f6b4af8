"""docker-compose.yml and its override files, beside the ``aiobt up`` config that runs
the same commands (the router by its container name; with mutual TLS, the
certificates of ``aiobt certs ... --host compose=router --seen-at /certs``)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.deploy.zenoh_configs import write_configs
from aiobt.system.config import SystemConfig, config_from_dict

REPO = Path(__file__).resolve().parents[1]
ROUTER_TLS = "tls/router:7447"  # the router, by its container's name
ROUTER_TCP = "tcp/router:7447"  # ... with user and password (docker-compose.userpass.yml)
IN_CONTAINERS = "/certs"  # where the containers mount deploy/compose-certs
PLAN = CertPlan(hosts={"compose": ("router",)})  # the router's certificate names "router"


def load(name: str) -> dict[str, Any]:
    loaded: dict[str, Any] = yaml.safe_load((REPO / name).read_text())
    return loaded


def make_certs(directory: Path) -> Path:
    """The compose deployment's certificates, with paths as this machine sees them."""
    write_certs(directory, PLAN)
    write_configs(directory, PLAN)
    return directory


def up_config(certs: Path | None, **settings: Any) -> SystemConfig:
    """``aiobt up``'s config for the compose commands: mutual TLS with ``certs`` (a
    directory of :func:`make_certs`), or user and password (None)."""
    router = (
        {"listen": ROUTER_TCP} if certs is None else {"listen": ROUTER_TLS, "certs": str(certs)}
    )
    return config_from_dict({"router": router, **settings}, "compose")


def in_containers(command: list[str], certs: Path) -> list[str]:
    """``command`` with ``certs`` where the containers mount the certificates."""
    return [arg.replace(str(certs), IN_CONTAINERS) for arg in command]
