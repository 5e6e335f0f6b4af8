"""The misbehaving link proxy on loopback, between a client and an echo server."""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncIterator
from pathlib import Path

import pytest

from tests.netlab.control import ProxyControl, apply, serve
from tests.netlab.proxy import LinkProxy

pytestmark = pytest.mark.timeout(30)
LOOPBACK = "127.0.0.1"


async def _echo(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    with contextlib.suppress(OSError):
        while data := await reader.read(65536):
            writer.write(data)
            await writer.drain()
    writer.close()


@pytest.fixture
async def proxy() -> AsyncIterator[LinkProxy]:
    server = await asyncio.start_server(_echo, LOOPBACK, 0)
    link = LinkProxy((LOOPBACK, 0), (LOOPBACK, server.sockets[0].getsockname()[1]), seed=1)
    await link.start()
    try:
        yield link
    finally:
        await link.close()
        server.close()


@contextlib.asynccontextmanager
async def dial(link: LinkProxy) -> AsyncIterator[tuple[asyncio.StreamReader, asyncio.StreamWriter]]:
    reader, writer = await asyncio.open_connection(LOOPBACK, link.port)
    try:
        yield reader, writer
    finally:
        writer.close()


async def round_trip(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> float:
    start = time.monotonic()
    writer.write(b"ping")
    await writer.drain()
    async with asyncio.timeout(5.0):
        assert await reader.readexactly(4) == b"ping"
    return time.monotonic() - start


async def test_a_healthy_link_forwards_both_ways(proxy: LinkProxy) -> None:
    async with dial(proxy) as (reader, writer):
        assert await round_trip(reader, writer) < 0.05
    assert proxy.stats.connections == 1
    assert proxy.stats.bytes_forwarded == 8


async def test_latency_and_jitter_delay_each_way_and_never_reorder(proxy: LinkProxy) -> None:
    proxy.set_latency(0.1, 0.03)
    async with dial(proxy) as (reader, writer):
        trips = [await round_trip(reader, writer) for _ in range(5)]
        assert all(0.14 <= trip <= 0.4 for trip in trips), trips
        assert len({round(t, 3) for t in trips}) > 1  # jitter: not all the same
        numbers = b"".join(b"%05d" % i for i in range(200))
        for i in range(200):  # one chunk each, each with its own jitter
            writer.write(numbers[i * 5 : i * 5 + 5])
            await writer.drain()
            await asyncio.sleep(0.001)
        async with asyncio.timeout(5.0):
            assert await reader.readexactly(len(numbers)) == numbers


async def test_the_bandwidth_cap_bounds_the_throughput(proxy: LinkProxy) -> None:
    proxy.set_bandwidth(100_000)
    payload = bytes(range(256)) * 160  # 40 960 bytes: 0.41 s one way at 100 kB/s
    async with dial(proxy) as (reader, writer):
        start = time.monotonic()
        writer.write(payload)
        await writer.drain()
        async with asyncio.timeout(10.0):
            assert await reader.readexactly(len(payload)) == payload
        took = time.monotonic() - start
    # the echo streams back while it streams in: one way's time, and the last chunk's
    assert 0.44 <= took <= 1.5, took


async def test_a_stall_holds_everything_then_delivers_it(proxy: LinkProxy) -> None:
    async with dial(proxy) as (reader, writer):
        proxy.stall(0.6)
        start = time.monotonic()
        writer.write(b"held")
        await writer.drain()
        with pytest.raises(TimeoutError):
            async with asyncio.timeout(0.4):
                await reader.readexactly(4)
        async with asyncio.timeout(5.0):
            assert await reader.readexactly(4) == b"held"
        assert 0.6 <= time.monotonic() - start <= 1.5


async def test_a_cut_drops_everything_and_restore_breaks_only_the_old_connections(
    proxy: LinkProxy,
) -> None:
    async with dial(proxy) as (old_reader, old_writer):
        await round_trip(old_reader, old_writer)
        proxy.cut()
        old_writer.write(b"lost")
        await old_writer.drain()
        async with dial(proxy) as (new_reader, new_writer):  # a reconnect during the cut
            new_writer.write(b"lost")
            await new_writer.drain()
            with pytest.raises(TimeoutError):
                async with asyncio.timeout(0.5):
                    await old_reader.readexactly(4)
            assert not new_reader.at_eof()
            proxy.restore()
            async with asyncio.timeout(5.0):  # their streams lost bytes: closed
                assert await old_reader.read() == b""
                assert await new_reader.read() == b""
        async with dial(proxy) as (reader, writer):  # the healed link works
            assert await round_trip(reader, writer) < 0.5
    assert proxy.stats.bytes_dropped >= 8
    assert proxy.stats.broken == 2


def test_bad_settings_are_refused_by_name() -> None:
    link = LinkProxy((LOOPBACK, 0), (LOOPBACK, 1))
    with pytest.raises(ValueError, match="jitter <= mean"):
        link.set_latency(0.01, 0.03)
    with pytest.raises(ValueError, match="bandwidth must be > 0"):
        link.set_bandwidth(0)
    assert apply(link, {"op": "shake"}) == {"ok": False, "error": "shake: unknown op 'shake'"}
    assert not apply(link, {"op": "stall"})["ok"]


async def test_the_control_socket_drives_a_proxy(tmp_path: Path, proxy: LinkProxy) -> None:
    socket_path = tmp_path / "link.sock"
    other = LinkProxy((LOOPBACK, 0), proxy.target)
    task = asyncio.create_task(serve(other, socket_path))
    try:
        async with asyncio.timeout(5.0):
            while not socket_path.exists():  # noqa: ASYNC110 (a file, no event to wait on)
                await asyncio.sleep(0.01)
        control = ProxyControl(socket_path)
        await asyncio.to_thread(control.latency, 0.05, 0.01)
        assert other.faults.latency == 0.05
        await asyncio.to_thread(control.cut)
        assert other.faults.cut
        await asyncio.to_thread(control.restore)
        stats = await asyncio.to_thread(control.stats)
        assert stats["connections"] == 0
        with pytest.raises(RuntimeError, match="jitter <= mean"):
            await asyncio.to_thread(control.latency, 0.0, 1.0)
    finally:
        task.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await task
