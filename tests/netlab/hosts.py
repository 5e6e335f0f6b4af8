"""Hosts in network namespaces, joined by veth pairs, with processes run inside them.

    with NetLab() as lab:                       # skips the test without CAP_NET_ADMIN
        robot, base = lab.host("robot"), lab.host("base")
        lab.link(robot, "198.18.0.1", base, "198.18.0.2")
        router = lab.spawn(robot, ["-m", "aiobt.cli.router", "--listen", ...])

Each host is a namespace of its own (``aiobt-<pid>-<n>-<name>``: several test runs
can share a machine), with loopback up and, per link, one end of a veth pair made
directly inside it (never in the machine's own namespace) with a /30 address. The
addresses come from 198.18.0.0/15 (RFC 2544: for tests) and exist only inside the
namespaces the lab made. A host reaches only the hosts it is linked to: a link
namespace in the middle (with a proxy in it) makes every byte between two hosts
pass the proxy. Everything is torn down in ``close`` (processes by PID, then the
namespaces, which takes their links with them).
"""

from __future__ import annotations

import contextlib
import ipaddress
import itertools
import os
import subprocess
import sys
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import TracebackType

import pytest

from aiobt.system.lifeline import popen_bound
from aiobt.testing.bus import ServiceProcess

TEST_NET = ipaddress.ip_network("198.18.0.0/15")
_counter = itertools.count()


class NetLabUnavailable(RuntimeError):
    """This machine does not let us make network namespaces (no CAP_NET_ADMIN?)."""


@dataclass(slots=True)
class Host:
    name: str
    namespace: str
    addresses: list[str] = field(default_factory=list)

    def exec_prefix(self) -> list[str]:
        return ["ip", "netns", "exec", self.namespace]


class HostProcess(ServiceProcess):
    """A child Python process run inside a host's namespace, stopped by PID (``ip netns
    exec`` replaces itself with the program: the PID is the program's)."""

    def __init__(
        self, host: Host, args: Sequence[str], env: Mapping[str, str] | None = None
    ) -> None:
        self.host = host
        self.args = list(args)
        handle, name = tempfile.mkstemp(prefix=f"aiobt-{host.name}-", suffix=".log")
        os.close(handle)
        self.log_path = Path(name)
        with self.log_path.open("wb") as log_file:
            self.popen = popen_bound(
                [*host.exec_prefix(), *_program(args)],
                stdout=log_file,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                env={**os.environ, **(env or {})},
            )


def _program(args: Sequence[str]) -> list[str]:
    """``python ARGS`` unless ``args`` names a program (``zenoh``, an absolute path)."""
    first = args[0] if args else ""
    return list(args) if first and not first.startswith("-") else [sys.executable, *args]


class NetLab:
    """A set of hosts (namespaces) and links; a context manager that tears it all down."""

    def __init__(self) -> None:
        self.prefix = f"aiobt-{os.getpid()}-{next(_counter)}"
        self.hosts: dict[str, Host] = {}
        self.processes: list[ServiceProcess] = []
        self._links = 0

    def __enter__(self) -> NetLab:
        check_available()
        return self

    def __exit__(
        self, kind: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()

    def host(self, name: str) -> Host:
        host = Host(name, f"{self.prefix}-{name}")
        _ip("netns", "add", host.namespace)
        self.hosts[name] = host
        self.run(host, "ip", "link", "set", "lo", "up")
        return host

    def link(self, a: Host, a_address: str, b: Host, b_address: str) -> tuple[str, str]:
        """A veth pair between ``a`` and ``b`` with these /30 addresses (from TEST_NET);
        the names of its ends (``a``'s, ``b``'s)."""
        for address in (a_address, b_address):
            if ipaddress.ip_address(address) not in TEST_NET:
                raise ValueError(f"{address} is outside {TEST_NET}, the range for tests")
        self._links += 1
        a_end, b_end = f"v{self._links}{a.name[:5]}", f"v{self._links}{b.name[:5]}"
        _ip(
            "link", "add", a_end, "netns", a.namespace, "type", "veth",
            "peer", "name", b_end, "netns", b.namespace,
        )  # fmt: skip
        for host, end, address in ((a, a_end, a_address), (b, b_end, b_address)):
            self.run(host, "ip", "addr", "add", f"{address}/30", "dev", end)
            self.run(host, "ip", "link", "set", end, "up")
            host.addresses.append(address)
        return a_end, b_end

    def run(self, host: Host, *command: str) -> str:
        """A short command inside ``host``; its output (an error names the command)."""
        return _checked([*host.exec_prefix(), *command])

    def spawn(
        self, host: Host, args: Sequence[str], env: Mapping[str, str] | None = None
    ) -> HostProcess:
        """``python ARGS`` (or a program) inside ``host``; stopped by ``close`` at the latest."""
        process = HostProcess(host, args, env)
        self.processes.append(process)
        return process

    def close(self) -> None:
        for process in reversed(self.processes):
            with contextlib.suppress(Exception):
                process.cleanup()
        self.processes.clear()
        for host in self.hosts.values():
            subprocess.run(["ip", "netns", "del", host.namespace], capture_output=True, check=False)
        self.hosts.clear()


def check_available() -> None:
    """Skips the calling test, with the reason, where namespaces cannot be made."""
    probe = f"aiobt-probe-{os.getpid()}"
    try:
        _ip("netns", "add", probe)
    except (NetLabUnavailable, FileNotFoundError) as exc:
        pytest.skip(f"network namespaces unavailable (needs root or CAP_NET_ADMIN): {exc}")
    subprocess.run(["ip", "netns", "del", probe], capture_output=True, check=False)


def _ip(*args: str) -> str:
    return _checked(["ip", *args])


def _checked(command: list[str]) -> str:
    done = subprocess.run(command, capture_output=True, text=True, timeout=10, check=False)
    if done.returncode != 0:
        raise NetLabUnavailable(f"{' '.join(command)}: {done.stderr.strip() or done.returncode}")
    return done.stdout
