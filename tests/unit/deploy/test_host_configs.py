"""deploy/robot-host.yaml and deploy/base-host.yaml are the shares the namespace
harness runs (tests/netlab/deployment.py), with the addresses of docs/deployment.md."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.system import catalog
from aiobt.system.config import config_from_dict
from tests.netlab import deployment

REPO = Path(__file__).resolve().parents[3]
DOC_ADDRESSES = {"robot": "192.0.2.10", "base": "192.0.2.20"}
LAB_ADDRESSES = {"robot": deployment.ROBOT, "base": deployment.BASE}


def _as_in_the_lab(shipped: dict[str, Any], certs: Path) -> dict[str, Any]:
    text = yaml.safe_dump(shipped)
    for host in ("robot", "base"):
        text = text.replace(DOC_ADDRESSES[host], LAB_ADDRESSES[host])
    loaded: dict[str, Any] = yaml.safe_load(text)
    if "connect" in loaded["router"]:  # in the lab, the robot router is dialled via the proxy
        assert loaded["router"]["connect"] == [f"tls/{deployment.ROBOT}:7447"]
        loaded["router"]["connect"] = [f"tls/{deployment.LINK_BASE}:7447"]
    loaded["router"]["certs"] = str(certs)
    loaded["router"]["access_control"] = str(deployment.ACCESS_CONTROL)
    args = loaded["router"]["args"]
    if "--downsampling" in args:
        args[args.index("--downsampling") + 1] = str(deployment.DOWNSAMPLING)
    return loaded


@pytest.mark.parametrize("host", ["robot", "base"])
def test_the_shipped_share_is_the_one_the_harness_runs(tmp_path: Path, host: str) -> None:
    write_certs(tmp_path, CertPlan())
    shipped = yaml.safe_load((REPO / "deploy" / f"{host}-host.yaml").read_text())
    assert _as_in_the_lab(shipped, tmp_path) == deployment.host_config(tmp_path, host)
    config = config_from_dict(shipped | {"router": shipped["router"] | {"certs": str(tmp_path)}})
    assert config.enabled() == [s for s in deployment.SERVICES if s in deployment.HOSTS[host]]


def test_the_two_shares_run_every_default_service_once(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    shares = [
        config_from_dict(deployment.host_config(tmp_path, host)).enabled()
        for host in ("robot", "base")
    ]
    assert sorted(shares[0] + shares[1]) == sorted(config_from_dict({}).enabled())
    assert {"robot", "controller", "behaviors"} <= set(shares[0])  # the loop on the robot
    assert {"planner", "navigator"} <= set(shares[1])


def test_a_host_the_catalog_does_not_know_is_refused_by_name() -> None:
    with pytest.raises(KeyError, match="no host 'lab' \\(known: robot, base\\)"):
        catalog.on_host("lab")
