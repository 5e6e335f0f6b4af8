"""Driving a :class:`LinkProxy` in another process (e.g. inside a network namespace).

    python -m tests.netlab.control --listen 198.18.0.6:7447 --target 198.18.0.1:7447 \\
        --control /tmp/link.sock

serves the proxy and, on the Unix socket ``--control`` (a file: reachable from any
namespace), one JSON command per line, answered with one JSON line: ``{"op":
"latency", "mean": 0.1, "jitter": 0.03}``, ``{"op": "bandwidth", "bytes_per_s":
125000}`` (null: no cap), ``{"op": "stall", "seconds": 5}``, ``{"op": "cut"}``,
``{"op": "restore"}``, ``{"op": "stats"}``. :class:`ProxyControl` sends them.
"""

from __future__ import annotations

import argparse
import asyncio
import dataclasses
import json
import signal
import socket
from pathlib import Path
from typing import Any

from tests.netlab.proxy import LinkProxy


def apply(proxy: LinkProxy, command: dict[str, Any]) -> dict[str, Any]:
    """Carry out one command; the answer has ``ok`` and the proxy's stats."""
    op = command.get("op")
    try:
        if op == "latency":
            proxy.set_latency(float(command["mean"]), float(command.get("jitter", 0.0)))
        elif op == "bandwidth":
            value = command.get("bytes_per_s")
            proxy.set_bandwidth(None if value is None else float(value))
        elif op == "stall":
            proxy.stall(float(command["seconds"]))
        elif op == "cut":
            proxy.cut()
        elif op == "restore":
            proxy.restore()
        elif op != "stats":
            raise ValueError(f"unknown op {op!r}")
    except (KeyError, TypeError, ValueError) as exc:
        return {"ok": False, "error": f"{op}: {exc}"}
    return {"ok": True, "stats": dataclasses.asdict(proxy.stats)}


class ProxyControl:
    """Sends commands to a proxy's control socket (blocking, bounded by ``timeout``)."""

    def __init__(self, path: str | Path, timeout: float = 5.0) -> None:
        self.path, self.timeout = str(path), timeout

    def send(self, **command: Any) -> dict[str, Any]:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as sock:
            sock.settimeout(self.timeout)
            sock.connect(self.path)
            sock.sendall(json.dumps(command).encode() + b"\n")
            answer: dict[str, Any] = json.loads(sock.makefile().readline())
        if not answer.get("ok"):
            raise RuntimeError(f"proxy refused {command}: {answer.get('error')}")
        return answer

    def latency(self, mean: float, jitter: float = 0.0) -> None:
        self.send(op="latency", mean=mean, jitter=jitter)

    def bandwidth(self, bytes_per_s: float | None) -> None:
        self.send(op="bandwidth", bytes_per_s=bytes_per_s)

    def stall(self, seconds: float) -> None:
        self.send(op="stall", seconds=seconds)

    def cut(self) -> None:
        self.send(op="cut")

    def restore(self) -> None:
        self.send(op="restore")

    def stats(self) -> dict[str, int]:
        stats: dict[str, int] = self.send(op="stats")["stats"]
        return stats


async def serve(proxy: LinkProxy, control: Path) -> None:
    async def on_command(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        try:
            line = await reader.readline()
            try:
                answer = apply(proxy, json.loads(line))
            except json.JSONDecodeError as exc:
                answer = {"ok": False, "error": f"not JSON: {exc}"}
            writer.write(json.dumps(answer).encode() + b"\n")
            await writer.drain()
        finally:
            writer.close()

    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    await proxy.start()
    server = await asyncio.start_unix_server(on_command, str(control))
    print(
        f"ready {proxy.listen[0]}:{proxy.port} -> {proxy.target[0]}:{proxy.target[1]}", flush=True
    )
    try:
        await stop.wait()
    finally:
        server.close()
        await proxy.close()
        await asyncio.to_thread(control.unlink, missing_ok=True)


def _address(text: str) -> tuple[str, int]:
    host, _, port = text.rpartition(":")
    return host, int(port)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--listen", type=_address, required=True, metavar="HOST:PORT")
    parser.add_argument("--target", type=_address, required=True, metavar="HOST:PORT")
    parser.add_argument("--control", type=Path, required=True, metavar="SOCKET")
    parser.add_argument("--seed", type=int, default=0, help="of the jitter (default: 0)")
    args = parser.parse_args()
    asyncio.run(serve(LinkProxy(args.listen, args.target, args.seed), args.control))


if __name__ == "__main__":
    main()
