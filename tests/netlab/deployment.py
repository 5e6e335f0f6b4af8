"""The deployment of docs/deployment.md, in namespaces: robot host, base host, a laptop.

    host    address(es)                  runs
    robot   198.18.0.1                   router-robot, robot, controller, behaviors (...)
    link    198.18.0.2, 198.18.0.6       the proxy: 198.18.0.6:7447 -> 198.18.0.1:7447
    base    198.18.0.5, 198.18.0.10      router-base, planner, navigator (...)
    laptop  198.18.0.9                   the zenoh CLI, scenarios (tests.netlab.scenario)

Each host runs its share with ``aiobt up --config <host>.yaml`` (mutual TLS with the
certificates of ``aiobt certs``, the access-control file of deploy/); the base router
joins the robot router through the proxy in the ``link`` namespace, so every byte
between the hosts passes it (the hosts have no other route to each other), and the
faults of :class:`~tests.netlab.control.ProxyControl` apply to the routers' link.
The laptop reaches the base router only (its default route is the base host).
Which services each host runs is the catalog's (``ServiceSpec.host``).
"""

from __future__ import annotations

import contextlib
import json
import sys
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.deploy.zenoh_configs import write_configs
from aiobt.system import catalog
from aiobt.system.config import config_from_dict
from tests.netlab.control import ProxyControl
from tests.netlab.hosts import HostProcess, NetLab

REPO = Path(__file__).resolve().parents[2]
ACCESS_CONTROL = REPO / "deploy" / "access-control.json5"
DOWNSAMPLING = REPO / "deploy" / "downsampling.json5"
SHIPPED_INTERFACE = "wlan0"  # the interface towards the base host in DOWNSAMPLING
ROBOT, LINK_ROBOT = "198.18.0.1", "198.18.0.2"
BASE, LINK_BASE = "198.18.0.5", "198.18.0.6"
LAPTOP, BASE_LAPTOP = "198.18.0.9", "198.18.0.10"
PORT = 7447
LOCAL = f"tls/127.0.0.1:{PORT}"  # where a host's own services reach its router
NAMESPACE = "robot"
# each host's share: the catalog's services on that host, as on (or off) as by default
HOSTS = {host: catalog.on_host(host) for host in catalog.HOSTS}
SERVICES = tuple(config_from_dict({}).enabled())  # what `aiobt up` runs by default
UP_TIMEOUT = 120.0  # s for each host's share to be up on 2 loaded cores
DEFAULT_LEASE_MS = 1000  # deploy/*-host.yaml's
# the lab's: on 2 cores shared with other work, a starved process must not be taken for
# a hung one (as tests/e2e's stack); a cut or a stall longer than this still drops links
LAB_LEASE_MS = 5000


def make_certs(directory: Path) -> Path:
    """The deployment's certificates: the robot router is dialled at its own address and
    at the proxy's (the base router goes through it), the base router at its own."""
    plan = CertPlan(hosts={"robot": (ROBOT, LINK_BASE), "base": (BASE,)})
    write_certs(directory, plan)
    write_configs(directory, plan)
    return directory


def host_config(
    certs: Path,
    host: str,
    lease_ms: int = DEFAULT_LEASE_MS,
    downsampling: Path = DOWNSAMPLING,
) -> dict[str, Any]:
    """``aiobt up``'s config of one host's share (what docs/deployment.md writes); the
    robot host's router thins what it sends the base host (``downsampling``)."""
    # the host's services on loopback (downsampling, by interface, passes them by); the
    # other host's router, the laptop, on the host's address
    router: dict[str, Any] = {
        "listen": LOCAL,
        "certs": str(certs),
        "host": host,
        "access_control": str(ACCESS_CONTROL),
        "args": ["--listen", f"tls/{ROBOT if host == 'robot' else BASE}:{PORT}",
                 "--lease-ms", str(lease_ms)],
    }  # fmt: skip
    if host == "robot":
        router["args"] += ["--downsampling", str(downsampling)]
    if host == "base":
        router["connect"] = [f"tls/{LINK_BASE}:{PORT}"]
    services: dict[str, Any] = {
        spec.name: {"enabled": spec.enabled and spec.host == host} for spec in catalog.SERVICES
    }
    if lease_ms != DEFAULT_LEASE_MS:
        for name in HOSTS[host]:
            services[name]["args"] = ["--lease-ms", str(lease_ms)]
    return {"namespace": NAMESPACE, "router": router, "services": services}


@dataclass
class Deployment:
    lab: NetLab
    certs: Path
    proxy: ProxyControl
    ups: dict[str, HostProcess]

    @property
    def base_endpoint(self) -> str:
        return f"tls/{BASE}:{PORT}"

    @property
    def robot_endpoint(self) -> str:
        return f"tls/{ROBOT}:{PORT}"

    def scenario(self, host: str, identity: str, args: Sequence[str]) -> HostProcess:
        """``tests.netlab.scenario ARGS`` in ``host`` as ``identity``, on that host's router
        on loopback (the laptop's: the base router, at the base's address)."""
        endpoint = self.base_endpoint if host == "laptop" else LOCAL
        return self.lab.spawn(
            self.lab.hosts[host],
            ["-m", "tests.netlab.scenario", "--connect", endpoint, "--namespace", NAMESPACE,
             "--config", str(self.certs / f"{identity}.json5"), "--connect-timeout", "30",
             "--lease-ms", str(LAB_LEASE_MS), *args],
        )  # fmt: skip

    def monitor(self) -> HostProcess:
        """``aiobt monitor --plain`` on the laptop, as ``laptop``, on the base router."""
        return self.lab.spawn(
            self.lab.hosts["laptop"],
            ["-m", "aiobt.cli.main", "monitor", "--plain", "--connect", self.base_endpoint,
             "--namespace", NAMESPACE, "--config", str(self.certs / "laptop.json5"),
             "--lease-ms", str(LAB_LEASE_MS)],
        )  # fmt: skip

    def zenoh_cli(self, identity: str, args: Sequence[str]) -> HostProcess:
        """The ``zenoh`` command line on the laptop, connected to the base router."""
        zenoh = str(Path(sys.executable).parent / "zenoh")
        return self.lab.spawn(
            self.lab.hosts["laptop"],
            [zenoh, "--mode", "client", "--connect", self.base_endpoint,
             "--config", str(self.certs / f"{identity}.json5"), *args],
        )  # fmt: skip

    def logs(self, tail: int = 6000) -> str:
        return "\n".join(
            f"--- {p.host.name if isinstance(p, HostProcess) else '?'}: {' '.join(p.args[:4])} "
            f"---\n{p.output()[-tail:]}"
            for p in self.lab.processes
        )


@contextlib.contextmanager
def deployment(tmp: Path, lease_ms: int = LAB_LEASE_MS) -> Iterator[Deployment]:
    """The lab, certificates, the proxy and both hosts' shares up (skips without
    namespaces); everything stopped and removed on exit."""
    with NetLab() as lab:
        robot, link, base, laptop = (lab.host(n) for n in ("robot", "link", "base", "laptop"))
        wan, _ = lab.link(robot, ROBOT, link, LINK_ROBOT)
        lab.link(base, BASE, link, LINK_BASE)
        lab.link(laptop, LAPTOP, base, BASE_LAPTOP)
        lab.run(laptop, "ip", "route", "add", "default", "via", BASE_LAPTOP)
        certs = make_certs(tmp / "certs")
        control = tmp / "link.sock"
        proxy = lab.spawn(
            link,
            ["-m", "tests.netlab.control", "--listen", f"{LINK_BASE}:{PORT}",
             "--target", f"{ROBOT}:{PORT}", "--control", str(control)],
        )  # fmt: skip
        if not proxy.wait_for_output("ready", 20.0):
            raise RuntimeError(f"the link proxy did not start:\n{proxy.output()}")
        thinning = tmp / "downsampling.json5"  # the shipped rules, on the lab's interface
        thinning.write_text(DOWNSAMPLING.read_text().replace(SHIPPED_INTERFACE, wan))
        ups = {}
        for name, host in (("robot", robot), ("base", base)):
            path = tmp / f"{name}.yaml"
            path.write_text(yaml.safe_dump(host_config(certs, name, lease_ms, thinning)))
            ups[name] = lab.spawn(host, ["-m", "aiobt.cli.main", "up", "--config", str(path),
                                         "--no-web", "--colour", "never"])  # fmt: skip
        yield Deployment(lab, certs, ProxyControl(control), ups)


def events(process: HostProcess) -> list[dict[str, Any]]:
    """The JSON events a scenario printed so far."""
    found = []
    for line in process.output().splitlines():
        if line.startswith('{"event"'):
            found.append(json.loads(line))
    return found


def event(process: HostProcess, name: str) -> dict[str, Any] | None:
    return next((e for e in events(process) if e["event"] == name), None)
