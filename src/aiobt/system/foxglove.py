"""``aiobt up --foxglove [PORT]`` and ``--mcap FILE``: the Foxglove bridge in the system.

The bridge (``aiobt foxglove``) runs as one more supervised child process: its
output is prefixed ``foxglove``, a crash restarts it (a recording then goes on
in ``FILE-1.mcap``), and it is stopped first, with time to close the MCAP file,
before the services and the router.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from aiobt.system.commands import process_argv
from aiobt.system.config import SystemConfig
from aiobt.system.runner import System
from aiobt.system.supervisor import Child

NAME = "foxglove"
STOP_GRACE = 5.0  # s for the bridge to close its MCAP file after SIGTERM


@dataclass(slots=True, frozen=True)
class FoxgloveOptions:
    port: int | None  # None: no WebSocket server (--mcap alone)
    mcap: Path | None
    host: str = "127.0.0.1"

    @property
    def wanted(self) -> bool:
        return self.port is not None or self.mcap is not None


def foxglove_command(config: SystemConfig, options: FoxgloveOptions) -> list[str]:
    command = [NAME, "--connect", config.router.listen, "--namespace", config.namespace]
    if options.port is None:
        command.append("--no-server")
    else:
        command += ["--host", options.host, "--port", str(options.port)]
    if options.mcap is not None:
        command += ["--mcap", str(options.mcap.resolve())]
    return command


async def start_foxglove(system: System, options: FoxgloveOptions) -> None:
    """Start the bridge; it is healthy while its token ``{ns}/nodes/foxglove`` lives."""
    assert system.bus is not None, "start_foxglove inside run_system"
    supervisor = system.supervisor
    argv = process_argv(foxglove_command(system.config, options))
    await supervisor.start(Child(NAME, argv))
    token = system.bus.presence(f"{system.config.namespace}/nodes/{NAME}")
    token.add_listener(lambda alive: supervisor.mark_healthy(NAME, alive))
    if token.present:
        supervisor.mark_healthy(NAME, True)


async def stop_foxglove(system: System) -> None:
    """Stop the bridge alone (SIGTERM, ``STOP_GRACE`` s to finish its recording)."""
    others = [name for name in system.supervisor.children if name != NAME]
    await system.supervisor.stop(keep=others, grace=STOP_GRACE)
