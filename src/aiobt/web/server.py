"""The web view's HTTP server: one page, its script, and a websocket per browser.

    async with serve_web(bus, WebOptions(port=8080)) as view:
        print(view.url)            # http://127.0.0.1:8080/
        await stop.wait()

The page (``static/``) gets one JSON object per update on ``/ws``: the streams
that changed since the previous one (see :mod:`aiobt.web.sources`), at most
``rate`` per second; a browser that reads slower gets fewer, newer updates
(:mod:`aiobt.web.coalesce`). The page sends ``{"goal": {"x", "y", "yaw"}}``
for a click on the map; the answer comes back on the ``goal_reply`` stream.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass, field
from importlib import resources

from aiohttp import WSCloseCode, WSMsgType, web

from aiobt.costmap.inflation import InflationParams
from aiobt.hosts import is_loopback
from aiobt.transport import Bus
from aiobt.web.coalesce import Hub, Outbox
from aiobt.web.sources import Sources

log = logging.getLogger("aiobt.web.server")
STATIC = resources.files("aiobt.web") / "static"
_FILES = {
    "/": "index.html",
    "/app.js": "app.js",
    "/localization.js": "localization.js",
    "/style.css": "style.css",
}
Handler = Callable[[web.Request], Awaitable[web.Response]]
_TYPES = {".html": "text/html", ".js": "text/javascript", ".css": "text/css"}


@dataclass(slots=True, frozen=True)
class WebOptions:
    host: str = "127.0.0.1"
    port: int = 8080
    rate: float = 20.0  # updates per second pushed to each browser, at most
    inflation: InflationParams = field(default_factory=InflationParams)

    def __post_init__(self) -> None:
        if not 0 <= self.port <= 65535:
            raise ValueError(f"web port {self.port} is not in 0..65535")
        if not 1.0 <= self.rate <= 100.0:
            raise ValueError(f"web update rate {self.rate} is not in 1..100 per second")


@dataclass(slots=True)
class WebView:
    """A running web view (see :func:`serve_web`)."""

    url: str
    hub: Hub
    sources: Sources


def warn_if_open(host: str, port: int) -> None:
    if not is_loopback(host):
        log.warning(
            "web view on %s:%d: reachable from other machines, with no authentication "
            "(anyone who can reach it can send the robot goals)", host, port,
        )  # fmt: skip


@contextlib.asynccontextmanager
async def serve_web(bus: Bus, options: WebOptions) -> AsyncIterator[WebView]:
    """Serve the page on ``options.host:port`` fed from ``bus`` until the block exits."""
    warn_if_open(options.host, options.port)
    hub = Hub()
    sources = Sources(bus, hub, options.inflation)
    sources.attach()
    app = web.Application()
    for path, name in _FILES.items():
        app.router.add_get(path, _file_handler(name))
    sockets: set[web.WebSocketResponse] = set()
    app.router.add_get("/ws", _socket_handler(hub, sources, sockets))
    # open websockets are closed first: a stop takes no more than the shutdown timeout
    runner = web.AppRunner(app, access_log=None, handle_signals=False, shutdown_timeout=1.0)
    await runner.setup()
    flushing: asyncio.Task[None] | None = None
    try:
        site = web.TCPSite(runner, options.host, options.port)
        try:
            await site.start()
        except OSError as exc:
            raise OSError(
                f"web view: cannot listen on {options.host}:{options.port}: {exc}"
            ) from exc
        host, port = runner.addresses[0][:2]
        view = WebView(f"http://{_url_host(host)}:{port}/", hub, sources)
        log.info("web view on %s (namespace '%s')", view.url, bus.namespace)
        flushing = asyncio.create_task(_flush_forever(sources, 1.0 / options.rate))
        yield view
    finally:
        if flushing is not None:
            flushing.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await flushing
        for ws in list(sockets):
            await ws.close(code=WSCloseCode.GOING_AWAY, message=b"web view stopping")
        await runner.cleanup()
        sources.close()


def _url_host(host: str) -> str:
    return f"[{host}]" if ":" in host else host


async def _flush_forever(sources: Sources, period: float) -> None:
    """The page's pace (wall time: what a screen shows, not robot time)."""
    while True:
        sources.flush()
        await asyncio.sleep(period)


def _file_handler(name: str) -> Handler:
    body = (STATIC / name).read_bytes()
    content_type = _TYPES[name[name.rindex(".") :]]

    async def handler(_request: web.Request) -> web.Response:
        return web.Response(body=body, content_type=content_type, charset="utf-8")

    return handler


def _socket_handler(
    hub: Hub, sources: Sources, sockets: set[web.WebSocketResponse]
) -> Callable[[web.Request], Awaitable[web.WebSocketResponse]]:
    async def handler(request: web.Request) -> web.WebSocketResponse:
        ws = web.WebSocketResponse(heartbeat=10.0, max_msg_size=64 * 1024)
        await ws.prepare(request)
        outbox = hub.join()
        sockets.add(ws)
        log.info("browser %s connected (%d open)", request.remote, hub.clients)
        sending = asyncio.create_task(_send_forever(ws, outbox))
        try:
            async for message in ws:
                if message.type == WSMsgType.TEXT:
                    await _on_message(message.data, sources, outbox)
        finally:
            hub.leave(outbox)
            sockets.discard(ws)
            sending.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await sending
            log.info("browser %s left (%d open)", request.remote, hub.clients)
        return ws

    return handler


async def _send_forever(ws: web.WebSocketResponse, outbox: Outbox) -> None:
    """Send what is pending whenever the socket has taken the previous update."""
    while not ws.closed:
        await outbox.ready.wait()
        frame = outbox.take()
        if frame is not None:
            try:
                await ws.send_str(frame)
            except ConnectionError:
                return


async def _on_message(text: str, sources: Sources, outbox: Outbox) -> None:
    goal, problem = parse_goal(text)
    if goal is not None:
        problem = await sources.send_goal(*goal)
    reply = {"ok": not problem, "error": problem, "goal": None if problem else goal}
    outbox.put("goal_reply", json.dumps(reply))
    if problem:
        log.warning("goal from the page refused: %s", problem)


def parse_goal(text: str) -> tuple[tuple[float, float, float] | None, str]:
    """``{"goal": {"x": .., "y": .., "yaw": ..}}`` -> ((x, y, yaw), "") or (None, why not)."""
    try:
        data = json.loads(text)
        goal = data["goal"]
        values = tuple(goal[k] for k in ("x", "y", "yaw"))
    except (ValueError, KeyError, TypeError) as exc:
        return None, f'page message {text[:80]!r}: expected {{"goal": {{x, y, yaw}}}} ({exc!r})'
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return None, f"goal {goal!r}: x, y and yaw must be numbers"
    x, y, yaw = (float(v) for v in values)
    return (x, y, yaw), ""
