"""``aiobt up --foxglove PORT --mcap FILE``: the bridge comes up with the system, serves
Foxglove clients, and its recording is closed when up stops."""

from __future__ import annotations

import asyncio
import signal
from pathlib import Path

import pytest
from mcap.reader import make_reader

from aiobt.testing.bus import free_port

from ..system.helpers import SystemProcess, processes_mentioning
from .wsclient import FoxgloveClient, Received

pytestmark = [pytest.mark.integration, pytest.mark.timeout(180)]


async def test_up_runs_the_bridge_and_closes_its_recording(endpoint: str, tmp_path: Path) -> None:
    port, recording = free_port(), tmp_path / "up.mcap"
    args = ["up", "--listen", endpoint, "--world", "small", "--speed", "2", "--namespace", "fox"]
    args.append("--no-web")
    with SystemProcess([*args, "--foxglove", str(port), "--mcap", str(recording)]) as up:
        up.wait_line("  foxglove * up")
        up.wait_line(f"Foxglove server on ws://127.0.0.1:{port}", timeout=5.0)
        fox = await FoxgloveClient.connect(f"ws://127.0.0.1:{port}")
        try:
            # the scan from the robot, the pose from localization (its estimate, once the
            # world's start is taken): both before the recording is closed
            await fox.wait_advertised({"/scan", "/pose"}, 20.0)
            await fox.subscribe("/scan")
            await fox.subscribe("/pose")
            got: dict[str, Received] = {}
            async with asyncio.timeout(30.0):
                while len(got) < 2:
                    message = await fox.receive()
                    got.setdefault(message.topic, message)
            scan = got["/scan"]
        finally:
            await fox.close()
        code, _ = up.stop(signal.SIGTERM)
    assert code == 0
    assert scan.topic == "/scan"
    assert len(scan.message.ranges) == 360
    assert processes_mentioning(endpoint) == []
    with recording.open("rb") as f:
        summary = make_reader(f).get_summary()  # None when the file was not closed
    assert summary is not None
    topics = {channel.topic for channel in summary.channels.values()}
    assert {"/map", "/scan", "/pose", "/tf"} <= topics, topics
    assert summary.statistics is not None
    assert summary.statistics.message_count > 10
