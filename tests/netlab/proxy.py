"""A TCP link that misbehaves on demand: latency and jitter, a bandwidth cap, a stall, a cut.

This kernel has no netem, so the link between two hosts' routers runs through this
proxy (asyncio, user space). Each accepted connection is joined to the target, and
each direction is a pipe that can:

- delay every chunk by ``latency`` ± ``jitter`` (uniform; never reordering bytes,
  as TCP would not: a chunk leaves no earlier than the one before it);
- cap the throughput at ``bytes_per_s`` (chunks of at most ``CHUNK`` bytes, each
  followed by its transmission time);
- stall: hold everything for N s, then deliver it (a Wi-Fi link that hangs);
- cut: drop everything, and accept new connections only to drop them too; on
  restore, the connections that lost data are closed (their byte streams are
  broken) and new ones work.

``LinkProxy`` is driven in-process (unit tests) or from another process through
:mod:`tests.netlab.control` (a proxy inside a network namespace).
"""

from __future__ import annotations

import asyncio
import contextlib
import random
import time
from dataclasses import dataclass, field

CHUNK = 4096  # bytes read at once: the granularity of the bandwidth cap
# bytes a direction holds (in flight or stalled) before it stops reading, so a slow or
# stalled link pushes back on the sender as a real one does (TCP's window), rather
# than queueing without end
BUFFER = 256 * 1024


@dataclass(slots=True)
class Faults:
    latency: float = 0.0
    jitter: float = 0.0
    bytes_per_s: float | None = None
    stalled_until: float = 0.0  # time.monotonic()
    cut: bool = False


@dataclass(slots=True)
class Stats:
    connections: int = 0
    bytes_forwarded: int = 0
    bytes_dropped: int = 0
    broken: int = 0  # connections closed on restore, having lost data in a cut


@dataclass(slots=True)
class _Pipe:
    reader: asyncio.StreamReader
    writer: asyncio.StreamWriter
    queue: asyncio.Queue[tuple[float, bytes]] = field(default_factory=asyncio.Queue)
    last_due: float = 0.0
    link_free: float = 0.0  # when the capped link has sent what it was given
    queued: int = 0
    room: asyncio.Event = field(default_factory=asyncio.Event)


@dataclass(slots=True, eq=False)
class _Connection:
    writers: list[asyncio.StreamWriter]

    def abort(self) -> None:
        for writer in self.writers:
            writer.transport.abort()


class LinkProxy:
    """Listens on ``listen``, forwards to ``target``, with :class:`Faults` applied."""

    def __init__(
        self, listen: tuple[str, int], target: tuple[str, int], seed: int | None = 0
    ) -> None:
        self.listen, self.target = listen, target
        self.faults = Faults()
        self.stats = Stats()
        self._random = random.Random(seed)
        self._server: asyncio.Server | None = None
        self._connections: set[_Connection] = set()
        self._lossy: set[_Connection] = set()  # connections that lost data in a cut
        self._tasks: set[asyncio.Task[None]] = set()  # the connections' handlers

    @property
    def port(self) -> int:
        assert self._server is not None, "not started"
        return int(self._server.sockets[0].getsockname()[1])

    async def start(self) -> None:
        self._server = await asyncio.start_server(self._accepted, *self.listen)

    async def close(self) -> None:
        if self._server is not None:
            self._server.close()
        for connection in list(self._connections):
            connection.abort()
        if self._tasks:  # each ends at once, its sockets aborted
            await asyncio.wait(self._tasks, timeout=2.0)
        if self._server is not None:
            with contextlib.suppress(asyncio.TimeoutError):
                async with asyncio.timeout(2.0):
                    await self._server.wait_closed()

    # -- the faults ---------------------------------------------------------------------------

    def set_latency(self, mean: float, jitter: float = 0.0) -> None:
        if mean < 0 or jitter < 0 or jitter > mean:
            raise ValueError(f"latency needs 0 <= jitter <= mean, got {mean} ± {jitter}")
        self.faults.latency, self.faults.jitter = mean, jitter

    def set_bandwidth(self, bytes_per_s: float | None) -> None:
        if bytes_per_s is not None and bytes_per_s <= 0:
            raise ValueError(f"bandwidth must be > 0 bytes/s, got {bytes_per_s}")
        self.faults.bytes_per_s = bytes_per_s

    def stall(self, seconds: float) -> None:
        self.faults.stalled_until = time.monotonic() + seconds

    def cut(self) -> None:
        self.faults.cut = True
        self._lossy |= self._connections

    def restore(self) -> None:
        """Heal a cut (closing the connections whose streams it broke) and end a stall."""
        self.faults.cut = False
        self.faults.stalled_until = 0.0
        for connection in self._lossy:
            connection.abort()
        self.stats.broken += len(self._lossy)
        self._lossy.clear()

    # -- the connections ----------------------------------------------------------------------

    async def _accepted(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        connection = _Connection([writer])
        task = asyncio.current_task()
        assert task is not None
        self._tasks.add(task)
        self._connections.add(connection)
        self.stats.connections += 1
        if self.faults.cut:
            self._lossy.add(connection)
        try:
            await self._join(reader, connection)
        except (OSError, asyncio.IncompleteReadError):
            pass
        finally:
            self._connections.discard(connection)
            self._lossy.discard(connection)
            self._tasks.discard(task)
            writer.close()

    async def _join(self, reader: asyncio.StreamReader, connection: _Connection) -> None:
        if self.faults.cut:  # a cut link: the far end is never reached
            await self._drain_to_nowhere(reader)
            return
        writer = connection.writers[0]
        far_reader, far_writer = await asyncio.open_connection(*self.target)
        connection.writers.append(far_writer)
        try:
            async with asyncio.TaskGroup() as group:
                for pipe in (_Pipe(reader, far_writer), _Pipe(far_reader, writer)):
                    group.create_task(self._read(pipe))
                    group.create_task(self._write(pipe))
        except* (OSError, asyncio.IncompleteReadError):
            pass  # one end closed or reset: the connection is over
        finally:
            far_writer.close()

    async def _drain_to_nowhere(self, reader: asyncio.StreamReader) -> None:
        while data := await reader.read(CHUNK):
            self.stats.bytes_dropped += len(data)

    async def _read(self, pipe: _Pipe) -> None:
        while data := await pipe.reader.read(CHUNK):
            if self.faults.cut:
                self.stats.bytes_dropped += len(data)
                continue
            delay = self.faults.latency + self._random.uniform(
                -self.faults.jitter, self.faults.jitter
            )
            pipe.last_due = max(pipe.last_due, time.monotonic() + delay)
            pipe.queue.put_nowait((pipe.last_due, data))
            pipe.queued += len(data)
            while pipe.queued > BUFFER:
                pipe.room.clear()
                await pipe.room.wait()
        raise ConnectionResetError("closed by the peer")  # ends the connection's group

    async def _write(self, pipe: _Pipe) -> None:
        while True:
            due, data = await pipe.queue.get()
            pipe.queued -= len(data)
            pipe.room.set()
            if self.faults.bytes_per_s:  # it arrives once the link has carried it
                start = max(time.monotonic(), pipe.link_free)
                pipe.link_free = start + len(data) / self.faults.bytes_per_s
                due = max(due, pipe.link_free)
            await _sleep_until(due)
            while self.faults.stalled_until > time.monotonic():  # a stall may be extended
                await _sleep_until(self.faults.stalled_until)
            if self.faults.cut:
                self.stats.bytes_dropped += len(data)
                continue
            pipe.writer.write(data)
            await pipe.writer.drain()
            self.stats.bytes_forwarded += len(data)


async def _sleep_until(due: float) -> None:
    wait = due - time.monotonic()
    if wait > 0:
        await asyncio.sleep(wait)
