"""A Groot2 stand-in for tests: a REQ client and a SUB for breakpoint notifications."""

from __future__ import annotations

import asyncio
import json
import random
import socket
import struct
from typing import Any

import zmq
import zmq.asyncio

HEADER = struct.Struct("<BBI")
TIMEOUT = 10.0


def free_port_pair() -> int:
    """A port P such that P and P + 1 are free on 127.0.0.1 right now, below the
    kernel's ephemeral range: a port the kernel handed out for binding to 0 is in that
    range, where any outgoing connection of the suite (Zenoh, ZeroMQ) can take it
    before the publisher binds it (a CI run: "Address already in use")."""
    low = 20000
    high = 32767
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range", encoding="ascii") as ranges:
            high = min(high, int(ranges.read().split()[0]) - 2)
    except (OSError, ValueError, IndexError):
        pass
    for _ in range(200):
        port = random.randrange(low, high)
        try:
            with socket.socket() as first, socket.socket() as second:
                first.bind(("127.0.0.1", port))
                second.bind(("127.0.0.1", port + 1))
        except OSError:
            continue
        return port
    raise RuntimeError(f"no free pair of ports on 127.0.0.1 in [{low}, {high})")


class Groot2Client:
    """Sends requests with increasing ids; every call is bounded by TIMEOUT."""

    def __init__(self, port: int) -> None:
        self.context = zmq.asyncio.Context()
        self.req = self.context.socket(zmq.REQ)
        self.req.setsockopt(zmq.LINGER, 0)
        self.req.connect(f"tcp://127.0.0.1:{port}")
        self.sub = self.context.socket(zmq.SUB)
        self.sub.setsockopt(zmq.LINGER, 0)
        self.sub.setsockopt(zmq.SUBSCRIBE, b"")
        self.handshake = self.sub.get_monitor_socket(zmq.EVENT_HANDSHAKE_SUCCEEDED)
        self.sub.connect(f"tcp://127.0.0.1:{port + 1}")
        self.next_id = 1000

    def close(self) -> None:
        self.sub.disable_monitor()
        self.handshake.close()
        self.req.close()
        self.sub.close()
        self.context.term()

    def header(self, kind: str) -> bytes:
        self.next_id += 1
        return HEADER.pack(2, ord(kind), self.next_id)

    async def raw(self, frames: list[bytes]) -> list[bytes]:
        await self.req.send_multipart(frames)
        reply: list[bytes] = await asyncio.wait_for(self.req.recv_multipart(), TIMEOUT)
        return reply

    async def request(self, kind: str, payload: bytes | str | None = None) -> list[bytes]:
        frames = [self.header(kind)]
        if payload is not None:
            frames.append(payload.encode() if isinstance(payload, str) else payload)
        return await self.raw(frames)

    async def hook_json(self, kind: str, body: Any) -> list[bytes]:
        return await self.request(kind, json.dumps(body))

    async def notification(self) -> list[bytes]:
        frames: list[bytes] = await asyncio.wait_for(self.sub.recv_multipart(), TIMEOUT)
        return frames

    async def subscribed(self) -> None:
        """Wait until the SUB's handshake with the PUB is done (its subscription is
        then on the wire; a PUB drops what it sends before the subscription arrives)."""
        await asyncio.wait_for(self.handshake.recv_multipart(), TIMEOUT)


def status_pairs(payload: bytes) -> list[tuple[int, int]]:
    return [struct.unpack_from("<HB", payload, i) for i in range(0, len(payload), 3)]


def transitions(payload: bytes) -> list[tuple[int, int, int]]:
    """(µs, uid, status) of a GET_TRANSITIONS payload."""
    out = []
    for offset in range(0, len(payload), 9):
        stamp = int.from_bytes(payload[offset : offset + 6], "little")
        uid, status = struct.unpack_from("<HB", payload, offset + 6)
        out.append((stamp, uid, status))
    return out
