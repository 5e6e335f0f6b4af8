"""How a service says it is up: its liveliness token and what it answers ``aiobt status``.

    announce(bus, "planner", sim_time=args.sim_time)

declares ``{ns}/nodes/planner`` (health for ``aiobt up`` and the tree's leaves)
and serves ``{ns}/srv/info/planner`` with a :class:`~aiobt.msgs.system.ServiceInfo`.
"""

from __future__ import annotations

import importlib.metadata
import os
import socket
import time

from aiobt.msgs import Empty
from aiobt.msgs.system import ServiceInfo
from aiobt.transport import Bus

DISTRIBUTION = "aiobt-runtime"


def version() -> str:
    try:
        return importlib.metadata.version(DISTRIBUTION)
    except importlib.metadata.PackageNotFoundError:
        return "unknown (not installed)"


def announce(bus: Bus, service: str, *, sim_time: bool, url: str = "") -> ServiceInfo:
    """Serve ``srv/info/{service}``, then declare the token ``nodes/{service}``
    (``url``: where a person opens it, for a web view)."""
    info = ServiceInfo(
        service=service,
        namespace=bus.namespace,
        version=version(),
        pid=os.getpid(),
        host=socket.gethostname(),
        sim_time=sim_time,
        started=time.time(),  # wall time by intent: when the process came up
        url=url,
    )
    bus.serve(f"info/{service}", Empty, ServiceInfo, lambda _request: info)
    bus.declare_token(f"nodes/{service}")
    return info
