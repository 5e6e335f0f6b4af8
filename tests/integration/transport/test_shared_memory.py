"""Shared memory is off in aiobt's sessions unless a config file asks for it.

Zenoh's default copies each message over 3 KB between processes of one host into
shared memory, set up on a process's first large messages (a 16 MB pool, mapped and
locked; those sends block 10-30 ms). A sender process, through a router that has
shared memory on, publishes large messages to a subscriber here; once three have
come it reports whether a Zenoh shared-memory segment is mapped in it
(``/proc/self/maps``).
"""

from __future__ import annotations

import asyncio
import json
import sys
import textwrap
from pathlib import Path

import pytest

from aiobt.testing.bus import running_router
from aiobt.transport import BusSettings, open_bus
from aiobt.transport.settings import SHARED_MEMORY_KEY

pytestmark = [
    pytest.mark.integration,
    pytest.mark.timeout(60),
    pytest.mark.skipif(sys.platform != "linux", reason="reads /proc/self/maps"),
]

SENDER = textwrap.dedent(
    """
    import select, sys, time, zenoh
    from aiobt.transport import BusSettings
    endpoint, config_file = sys.argv[1], sys.argv[2]
    if config_file == "zenoh-defaults":
        config = zenoh.Config()
        config.insert_json5("mode", '"client"')
        config.insert_json5("connect/endpoints", f'["{endpoint}"]')
    else:
        config = BusSettings(connect=(endpoint,), config_file=config_file or None).zenoh_config()
    with zenoh.open(config) as session:
        publisher = session.declare_publisher("robot/shm_probe")
        deadline = time.monotonic() + 20.0
        while not publisher.matching_status.matching:
            if time.monotonic() > deadline:
                sys.exit("no subscriber matched")
            time.sleep(0.01)
        # until the test has received three (with shared memory on, Zenoh 1.10.2
        # sometimes loses such a message: the test would otherwise wait in vain)
        while not select.select([sys.stdin], [], [], 0.05)[0]:
            publisher.put(b"x" * 60_000)
            if time.monotonic() > deadline:
                sys.exit("the test did not say it received three")
        sys.stdin.readline()
        with open("/proc/self/maps") as maps:
            mapped = any(line.rstrip().endswith(".zenoh") for line in maps)
        print("shared memory" if mapped else "none", flush=True)
    """
)


def sender_maps_shared_memory(endpoint: str, config_file: str) -> bool:
    """Run the sender, receive three of its large messages, return what it reports."""

    async def run() -> bool:
        async with open_bus(BusSettings(connect=(endpoint,))) as bus:
            received = asyncio.Queue[bytes]()
            loop = asyncio.get_running_loop()
            subscriber = bus.session.declare_subscriber(
                "robot/shm_probe",
                lambda sample: loop.call_soon_threadsafe(
                    received.put_nowait, sample.payload.to_bytes()
                ),
            )
            pipe = asyncio.subprocess.PIPE
            proc = await asyncio.create_subprocess_exec(
                sys.executable, "-c", SENDER, endpoint, config_file,
                stdin=pipe, stdout=pipe, stderr=pipe,
            )  # fmt: skip
            try:
                for _ in range(3):
                    payload = await asyncio.wait_for(received.get(), 30.0)
                    assert len(payload) == 60_000
                out, err = await asyncio.wait_for(proc.communicate(b"received\n"), 30.0)
            finally:
                subscriber.undeclare()  # type: ignore[no-untyped-call]
                if proc.returncode is None:
                    proc.kill()
                    await proc.wait()
            assert proc.returncode == 0, err.decode()
            return out.decode().split() == ["shared", "memory"]

    return asyncio.run(run())


def test_sessions_share_no_memory_unless_a_config_file_turns_it_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)
    shm_on = tmp_path / "shm_on.json5"
    shm_on.write_text("{transport: {shared_memory: {enabled: true}}}")
    with running_router(extra_args=["--config", str(shm_on)]) as (_, endpoint):
        # the control: Zenoh's defaults do map shared memory on this router
        assert sender_maps_shared_memory(endpoint, "zenoh-defaults")
        assert not sender_maps_shared_memory(endpoint, "")
        assert sender_maps_shared_memory(endpoint, str(shm_on))


def test_shared_memory_setting_follows_the_config_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)

    def enabled(text: str | None) -> bool:
        path = None
        if text is not None:
            path = tmp_path / "zenoh.json5"
            path.write_text(text)
        config = BusSettings(config_file=str(path) if path else None).zenoh_config()
        return bool(json.loads(config.get_json(SHARED_MEMORY_KEY)))

    assert not enabled(None)
    assert not enabled('{mode: "client"}')  # a file silent about it: our default
    assert enabled("{transport: {shared_memory: {enabled: true}}}")
    assert not enabled("{transport: {shared_memory: {enabled: false}}}")
