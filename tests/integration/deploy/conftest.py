"""A mutual-TLS router with the deployment's access-control file, and its certificates."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from aiobt.deploy.certs import SERVICES, CertPlan, write_certs
from aiobt.deploy.zenoh_configs import write_configs
from aiobt.testing.bus import ServiceProcess, running_router
from aiobt.transport.endpoints import free_port

REPO = Path(__file__).resolve().parents[3]
ACCESS_CONTROL = REPO / "deploy" / "access-control.json5"


# every identity, and localization's before the catalog runs it (the rules name it)
IDENTITIES = tuple(dict.fromkeys((*SERVICES, "localization")))


def make_certs(directory: Path, plan: CertPlan | None = None, renew: bool = False) -> Path:
    plan = plan or CertPlan(services=IDENTITIES)
    write_certs(directory, plan, renew=renew)
    write_configs(directory, plan)
    return directory


@pytest.fixture(scope="module")
def certs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_certs(tmp_path_factory.mktemp("certs"))


@pytest.fixture(scope="module")
def other_ca_certs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Certificates with the same names, from another deployment's CA."""
    return make_certs(tmp_path_factory.mktemp("other-certs"))


@pytest.fixture(scope="module")
def secure_router(certs: Path) -> Iterator[tuple[ServiceProcess, str]]:
    """The robot host's router: mutual TLS, the access-control file, on loopback."""
    args = [
        "--config",
        str(certs / "router-robot.json5"),
        "--access-control",
        str(ACCESS_CONTROL),
    ]
    with running_router(f"tls/127.0.0.1:{free_port()}", args) as (router, endpoint):
        assert router.wait_for_output("listening on", 10.0), router.output()
        yield router, endpoint
