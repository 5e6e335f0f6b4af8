"""Endpoints on this machine: a free loopback port for a router started here."""

from __future__ import annotations

import socket

LOOPBACK = "127.0.0.1"


def free_port() -> int:
    """A TCP port free on loopback right now (bind to port 0)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind((LOOPBACK, 0))
        return int(sock.getsockname()[1])


def free_endpoint() -> str:
    """``tcp/127.0.0.1:PORT`` on a port free right now."""
    return f"tcp/{LOOPBACK}:{free_port()}"
