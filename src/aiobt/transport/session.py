"""Opening the one Zenoh session of a process: retried while the router is absent."""

from __future__ import annotations

import asyncio
import logging
import threading
import time

import zenoh

from aiobt.transport import _z
from aiobt.transport.settings import BusSettings

log = logging.getLogger("aiobt.transport.session")
_RETRY_DELAYS = (0.1, 0.2, 0.5, 1.0)
_LAST_ATTEMPT = 1.0  # s an attempt may take past the deadline (refused: answered at once)


class BusUnavailable(ConnectionError):
    """The router could not be reached within ``connect_timeout``."""


async def open_session(settings: BusSettings) -> zenoh.Session:
    """Open the session, retrying (with back-off) until the router answers.

    Gives up with :class:`BusUnavailable` after ``settings.connect_timeout``
    seconds if one is set (a last attempt is made at that time); retries forever
    otherwise, logging every few seconds. Each attempt runs in a worker thread,
    so the event loop (and its signal handlers) keeps running while Zenoh
    connects; cancelling the wait closes a session that opens too late.
    """
    start = time.monotonic()
    deadline = None if settings.connect_timeout is None else start + settings.connect_timeout
    attempt = 0
    last_log = start
    while True:
        config = settings.zenoh_config()  # a Config is consumed by open()
        try:
            return await _open_in_thread(config, deadline)
        except (zenoh.ZError, TimeoutError) as exc:
            now = time.monotonic()
            if deadline is not None and now >= deadline:
                why = "no answer" if isinstance(exc, TimeoutError) else str(exc)
                raise BusUnavailable(
                    f"cannot open the Zenoh session ({_where(settings)}) after "
                    f"{now - start:.1f} s: {why}"
                ) from None
            if attempt == 0 or now - last_log > 5.0:
                log.warning("Zenoh not reachable (%s), retrying: %s", _where(settings), exc)
                last_log = now
        delay = _RETRY_DELAYS[min(attempt, len(_RETRY_DELAYS) - 1)]
        if deadline is not None:
            delay = max(0.0, min(delay, deadline - time.monotonic()))
        attempt += 1
        await asyncio.sleep(delay)


class _Attempt:
    """One ``zenoh.open`` in a worker thread; a session opened after the caller gave up
    (cancelled, or past the deadline) is closed, never leaked (it would hang the exit)."""

    def __init__(self, config: zenoh.Config) -> None:
        self._config = config
        self._lock = threading.Lock()
        self._abandoned = False
        self._session: zenoh.Session | None = None

    def run(self) -> zenoh.Session | None:
        session = zenoh.open(self._config)
        with self._lock:
            if not self._abandoned:
                self._session = session  # handed over: abandon() from now on closes it
                return session
        _z.close(session)
        return None

    def abandon(self) -> None:
        with self._lock:
            self._abandoned = True
            late, self._session = self._session, None
        if late is not None:
            _z.close(late)


async def _open_in_thread(config: zenoh.Config, deadline: float | None) -> zenoh.Session:
    """``zenoh.open`` in a thread of its own that ends with the attempt (no thread
    outlives the open; a pool's idle thread would)."""
    loop = asyncio.get_running_loop()
    future: asyncio.Future[zenoh.Session | None] = loop.create_future()
    attempt = _Attempt(config)

    def work() -> None:
        try:
            outcome: tuple[zenoh.Session | None, BaseException | None] = (attempt.run(), None)
        except BaseException as exc:  # handed to the awaiting task
            outcome = (None, exc)
        try:
            loop.call_soon_threadsafe(_settle, future, *outcome)
        except RuntimeError:  # the loop is gone; its task was cancelled and abandoned us
            attempt.abandon()

    # not a daemon: a daemon thread still inside Zenoh when the interpreter exits aborts
    # the process; an abandoned attempt ends by itself (Zenoh's connect is bounded)
    thread = threading.Thread(target=work, name="aiobt-zenoh-open")
    thread.start()
    # the attempt due at the deadline still gets time to answer
    timeout = None if deadline is None else max(_LAST_ATTEMPT, deadline - time.monotonic())
    try:
        async with asyncio.timeout(timeout):
            session = await future
    except BaseException:  # cancelled, or the deadline passed while Zenoh was connecting
        attempt.abandon()
        raise
    thread.join(1.0)  # it has handed the session over and is returning
    assert session is not None  # only an abandoned attempt gives None
    return session


def _settle(
    future: asyncio.Future[zenoh.Session | None],
    session: zenoh.Session | None,
    error: BaseException | None,
) -> None:
    if future.done():  # the waiter gave up: abandon() closes the session
        return
    if error is not None:
        future.set_exception(error)
    else:
        future.set_result(session)


def _where(settings: BusSettings) -> str:
    endpoints = ", ".join(settings.connect) or "default endpoints"
    return f"mode {settings.mode or 'client'}, connect {endpoints}"
