"""The namespace harness itself: hosts reach only the hosts they are linked to, a proxy
in a middle namespace carries every byte between two hosts, and nothing outlives it."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from tests.netlab.hosts import NetLab

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]

ECHO = (
    "import socket, sys\n"
    "s = socket.create_server((sys.argv[1], 7000)); print('ready', flush=True)\n"
    "while True:\n"
    "    c, _ = s.accept(); c.sendall(c.recv(64)); c.close()\n"
)
DIAL = (
    "import socket, sys\n"
    "try:\n"
    "    c = socket.create_connection((sys.argv[1], int(sys.argv[2])), timeout=1.0)\n"
    "    c.sendall(b'hello'); print(c.recv(64).decode())\n"
    "except OSError as e:\n"
    "    print('unreachable', type(e).__name__)\n"
)


def dial(lab: NetLab, host: str, address: str, port: int = 7000) -> str:
    return lab.run(lab.hosts[host], sys.executable, "-c", DIAL, address, str(port)).strip()


def test_hosts_reach_their_neighbours_only_through_the_links_made() -> None:
    with NetLab() as lab:
        robot, link, base = lab.host("robot"), lab.host("link"), lab.host("base")
        lab.link(robot, "198.18.0.1", link, "198.18.0.2")
        lab.link(base, "198.18.0.5", link, "198.18.0.6")
        echo = lab.spawn(robot, ["-c", ECHO, "198.18.0.1"])
        assert echo.wait_for_output("ready", 10.0), echo.output()
        assert dial(lab, "link", "198.18.0.1") == "hello"
        assert dial(lab, "base", "198.18.0.1").startswith("unreachable")  # no route
        proxy = lab.spawn(
            link,
            ["-m", "tests.netlab.control", "--listen", "198.18.0.6:7001",
             "--target", "198.18.0.1:7000", "--control", f"/tmp/{lab.prefix}.sock"],
        )  # fmt: skip
        assert proxy.wait_for_output("ready", 10.0), proxy.output()
        assert dial(lab, "base", "198.18.0.6", 7001) == "hello"  # through the proxy
        namespaces = [host.namespace for host in lab.hosts.values()]
        pids = [p.pid for p in lab.processes]
    listed = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout
    assert not any(ns in listed for ns in namespaces), listed
    for pid in pids:
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)


def test_addresses_outside_the_test_range_are_refused() -> None:
    with NetLab() as lab:
        a, b = lab.host("a"), lab.host("b")
        with pytest.raises(ValueError, match=r"outside 198\.18\.0\.0/15"):
            lab.link(a, "10.0.0.1", b, "10.0.0.2")


def test_the_machine_itself_gets_no_test_address() -> None:
    with NetLab() as lab:
        lab.link(lab.host("a"), "198.18.0.1", lab.host("b"), "198.18.0.2")
        here = subprocess.run(["ip", "-o", "addr"], capture_output=True, text=True).stdout
        assert "198.18." not in here
