"""A minimal Foxglove ws-protocol v1 client for the tests (the ``websockets`` package).

Receives ``advertise``, sends ``subscribe``, decodes binary message frames
(opcode 0x01, uint32 subscription id, uint64 timestamp, payload) with the
channel's protobuf/JSON schema; advertises client channels and publishes on them
(opcode 0x01, uint32 channel id, payload).
"""

from __future__ import annotations

import asyncio
import base64
import json
import struct
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import websockets
from mcap.records import Schema
from mcap_protobuf.decoder import DecoderFactory

# foxglove-sdk 0.30 accepts only "foxglove.sdk.v1", ws-protocol v1's successor with the
# same frames for what is used here; the client offers both, as Foxglove does
SUBPROTOCOLS = ["foxglove.sdk.v1", "foxglove.websocket.v1"]
_MESSAGE_DATA = 0x01
_HEADER = struct.Struct("<BIQ")
_CLIENT_HEADER = struct.Struct("<BI")


@dataclass(slots=True)
class Received:
    topic: str
    log_time: int
    message: Any  # a decoded protobuf message, or a dict for JSON channels


def payload_decoder(encoding: str, schema_name: str, schema: str, schema_encoding: str
                    ) -> Callable[[bytes], Any]:  # fmt: skip
    if encoding == "json":
        return json.loads
    data = base64.b64decode(schema)
    record = Schema(id=1, name=schema_name, encoding=schema_encoding, data=data)
    decode = DecoderFactory().decoder_for(encoding, record)
    assert decode is not None, f"no decoder for {encoding} {schema_name}"
    return decode


class FoxgloveClient:
    def __init__(self, ws: websockets.ClientConnection) -> None:
        self.ws = ws
        self.channels: dict[str, dict[str, Any]] = {}  # topic -> advertised channel
        self._subs: dict[int, tuple[str, Callable[[bytes], Any]]] = {}
        self.server_info: dict[str, Any] = {}

    @classmethod
    async def connect(cls, url: str, timeout: float = 10.0) -> FoxgloveClient:  # noqa: ASYNC109
        connecting = websockets.connect(url, subprotocols=SUBPROTOCOLS)  # type: ignore[arg-type]
        ws = await asyncio.wait_for(connecting, timeout)
        assert ws.subprotocol in SUBPROTOCOLS
        return cls(ws)

    async def wait_advertised(self, topics: set[str], timeout: float) -> None:  # noqa: ASYNC109
        async with asyncio.timeout(timeout):
            while not topics <= self.channels.keys():
                self._control(await self.ws.recv())

    def _control(self, frame: str | bytes) -> Received | None:
        if isinstance(frame, bytes):
            return self._data(frame)
        msg = json.loads(frame)
        if msg["op"] == "serverInfo":
            self.server_info = msg
        elif msg["op"] == "advertise":
            for channel in msg["channels"]:
                self.channels[channel["topic"]] = channel
        return None

    def _data(self, frame: bytes) -> Received | None:
        if frame[0] != _MESSAGE_DATA:
            return None
        _, sub_id, log_time = _HEADER.unpack_from(frame)
        topic, decode = self._subs[sub_id]
        return Received(topic, log_time, decode(frame[_HEADER.size :]))

    async def subscribe(self, *topics: str) -> None:
        subscriptions = []
        for topic in topics:
            ch = self.channels[topic]
            sub_id = len(self._subs) + 1
            decode = payload_decoder(
                ch["encoding"], ch["schemaName"], ch.get("schema", ""), ch.get("schemaEncoding", "")
            )
            self._subs[sub_id] = (topic, decode)
            subscriptions.append({"id": sub_id, "channelId": ch["id"]})
        await self.ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))

    async def receive(self) -> Received:
        """The next message on a subscribed channel (control frames are handled)."""
        while True:
            got = self._control(await self.ws.recv())
            if got is not None:
                return got

    async def advertise(self, channel_id: int, topic: str, schema_name: str) -> None:
        channel = {"id": channel_id, "topic": topic, "encoding": "json", "schemaName": schema_name}
        await self.ws.send(json.dumps({"op": "advertise", "channels": [channel]}))

    async def publish(self, channel_id: int, message: dict[str, Any]) -> None:
        payload = json.dumps(message).encode()
        await self.ws.send(_CLIENT_HEADER.pack(_MESSAGE_DATA, channel_id) + payload)

    async def close(self) -> None:
        await self.ws.close()
