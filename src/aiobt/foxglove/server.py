"""Run the bridge: a Foxglove WebSocket server and/or an MCAP recording.

The server's listener runs on the SDK's threads: a message a client publishes
is handed to the event loop (``call_soon_threadsafe``) and forwarded there.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import threading
from collections.abc import AsyncIterator
from dataclasses import dataclass
from pathlib import Path

import foxglove
from foxglove.websocket import (
    Capability,
    ChannelView,
    Client,
    ClientChannel,
    ServerListener,
    WebSocketServer,
)

from aiobt.foxglove.bridge import DEFAULT_COSTMAP_PERIOD, DEFAULT_FOOTPRINT_RADIUS, FoxgloveBridge
from aiobt.foxglove.channels import GOAL_TOPIC, INITIALPOSE_TOPIC
from aiobt.foxglove.recording import open_mcap
from aiobt.transport import Bus
from aiobt.transport.announce import announce

log = logging.getLogger("aiobt.foxglove.server")

LOCAL_HOST = "127.0.0.1"
DEFAULT_PORT = 8765


@dataclass(slots=True, frozen=True)
class BridgeOptions:
    host: str = LOCAL_HOST
    port: int | None = DEFAULT_PORT  # None: no WebSocket server (a recording only)
    mcap: Path | None = None
    overwrite: bool = False  # False: an existing recording is kept, the new one numbered
    footprint_radius: float = DEFAULT_FOOTPRINT_RADIUS
    costmap_period: float = DEFAULT_COSTMAP_PERIOD  # 0: no /global_costmap


def recording_path(path: Path, overwrite: bool) -> Path:
    """``path``, or the first free ``<stem>-<n><suffix>`` beside it when it exists (a
    restarted bridge never overwrites the recording of the run before)."""
    if overwrite or not path.exists():
        return path
    n = 1
    while (numbered := path.with_name(f"{path.stem}-{n}{path.suffix}")).exists():
        n += 1
    return numbered


class _GoalListener(ServerListener):
    """Client channels on :data:`GOAL_TOPIC` -> ``bridge.forward_goal`` and on
    :data:`INITIALPOSE_TOPIC` -> ``bridge.forward_initialpose``, in the loop."""

    def __init__(self, bridge: FoxgloveBridge, loop: asyncio.AbstractEventLoop) -> None:
        self._bridge = bridge
        self._loop = loop
        self._topics: dict[tuple[int, int], str] = {}
        self._lock = threading.Lock()
        self._forward = {
            GOAL_TOPIC: bridge.forward_goal, INITIALPOSE_TOPIC: bridge.forward_initialpose,
        }  # fmt: skip

    def on_client_advertise(self, client: Client, channel: ClientChannel) -> None:
        with self._lock:
            self._topics[(client.id, channel.id)] = channel.topic
        if channel.topic not in self._forward:
            log.info("client %d advertised %s: only %s are forwarded", client.id,
                     channel.topic, " and ".join(self._forward))  # fmt: skip

    def on_client_unadvertise(self, client: Client, client_channel_id: int) -> None:
        with self._lock:
            self._topics.pop((client.id, client_channel_id), None)

    def on_message_data(self, client: Client, client_channel_id: int, data: bytes) -> None:
        with self._lock:
            topic = self._topics.get((client.id, client_channel_id))
        if topic is not None and (forward := self._forward.get(topic)) is not None:
            self._loop.call_soon_threadsafe(forward, bytes(data), topic)

    def on_subscribe(self, client: Client, channel: ChannelView) -> None:
        log.debug("client %d subscribed to %s", client.id, channel.topic)


@contextlib.asynccontextmanager
async def running_bridge(bus: Bus, options: BridgeOptions) -> AsyncIterator[FoxgloveBridge]:
    """The bridge on ``bus`` with its server and recording, stopped on exit."""
    if options.host not in (LOCAL_HOST, "localhost", "::1"):
        log.warning("Foxglove server bound to %s: reachable from other machines, "
                    "and anyone reaching it can send the robot goals", options.host)  # fmt: skip
    context = foxglove.Context()
    bridge = FoxgloveBridge(bus, context, options.footprint_radius, options.costmap_period)
    with contextlib.ExitStack() as stack:
        if options.mcap is not None:
            path = recording_path(options.mcap, options.overwrite)
            try:
                writer = open_mcap(path, context, options.overwrite)
            except OSError as exc:
                raise OSError(f"--mcap {exc}") from None
            stack.callback(writer.close)
            log.info("recording to %s", path)
        if options.port is not None:
            server = _start_server(bridge, context, options)
            stack.callback(server.stop)
            log.info("Foxglove server on ws://%s:%d", options.host, server.port)
        bridge.start()
        announce(bus, "foxglove", sim_time=False)  # health for aiobt up, aiobt status lists it
        try:
            yield bridge
        finally:
            bridge.close()


def _start_server(
    bridge: FoxgloveBridge, context: foxglove.Context, options: BridgeOptions
) -> WebSocketServer:
    listener = _GoalListener(bridge, asyncio.get_running_loop())
    try:
        return foxglove.start_server(
            name=f"aiobt {bridge.bus.namespace}",
            host=options.host,
            port=options.port,
            capabilities=[Capability.ClientPublish],
            supported_encodings=["json"],
            server_listener=listener,
            context=context,
        )
    except RuntimeError as exc:  # the SDK's FoxgloveError: bind failures, bad host
        raise OSError(f"Foxglove server on {options.host}:{options.port}: {exc}") from None
