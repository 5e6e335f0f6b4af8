"""The Zenoh config file of each identity: which certificate its sessions present.

``aiobt certs DIR`` writes ``DIR/<name>.json5`` next to each certificate, so a
service joins a mutual-TLS deployment with ``--config DIR/<name>.json5 --connect
tls/HOST:7447`` and nothing else; a router's file also says where it listens from
(its certificate, for the sessions it accepts) and requires a client certificate.
Paths in the files are absolute, so they work from any working directory; with
``seen_at`` they name the directory where the processes that read them find it
(``/certs`` in docker-compose.yml's containers, which mount it there).
Endpoints, the mode of a service and the access-control rules are not in them:
they belong to the deployment (flags, ``aiobt up``'s config, deploy/).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from aiobt.deploy.certs import CA_NAME, CertPlan, cert_path, key_path, router_name

TLS_KEY = "transport/link/tls"


def client_tls(directory: Path, name: str) -> dict[str, Any]:
    """The ``transport.link.tls`` section of a session that presents ``name``'s certificate."""
    directory = directory.resolve()
    return {
        "root_ca_certificate": str(cert_path(directory, CA_NAME)),
        "enable_mtls": True,
        "connect_certificate": str(cert_path(directory, name)),
        "connect_private_key": str(key_path(directory, name)),
    }


def router_tls(directory: Path, name: str) -> dict[str, Any]:
    """A router's: it presents ``name``'s certificate both to the sessions it accepts
    and to the routers it connects to, and accepts only certificates of the CA."""
    directory = directory.resolve()
    return {
        **client_tls(directory, name),
        "listen_certificate": str(cert_path(directory, name)),
        "listen_private_key": str(key_path(directory, name)),
    }


def config_text(tls: dict[str, Any], *, router: bool) -> str:
    body: dict[str, Any] = {"transport": {"link": {"tls": tls}}}
    if router:
        body = {"mode": "router", **body}
    return "// written by `aiobt certs`: this identity's certificate for mutual TLS\n" + (
        json.dumps(body, indent=2) + "\n"
    )


def write_configs(directory: Path, plan: CertPlan, seen_at: Path | None = None) -> list[Path]:
    """Every identity's config file of ``plan``, in ``directory``, naming the files as
    they are seen at ``seen_at`` (default: ``directory`` itself, absolute)."""
    routers = {router_name(host) for host in plan.hosts}
    return [write_config(directory, n, router=n in routers, seen_at=seen_at) for n in plan.names()]


def write_config(directory: Path, name: str, *, router: bool, seen_at: Path | None = None) -> Path:
    where = seen_at or directory
    tls = router_tls(where, name) if router else client_tls(where, name)
    path = config_path(directory, name)
    path.write_text(config_text(tls, router=router), encoding="utf-8")
    return path


def config_path(directory: Path, name: str) -> Path:
    return directory / f"{name}.json5"
