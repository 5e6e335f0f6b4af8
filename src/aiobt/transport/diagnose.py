"""Why a Zenoh session did not open, in words a user can act on.

Zenoh says "Unable to connect to any of [...]! at /root/.cargo/...rs:447." both
when nothing listens and when the router refuses the credentials. A refused
session is told apart by knocking on the endpoint's TCP port: if it answers,
a router is there and refused (or never finished) the session handshake.
"""

from __future__ import annotations

import re
import socket

from aiobt.transport.tls_check import TlsFiles, tls_problem

_RUST_PLACE = re.compile(r"\s*\bat /\S+\.rs:\d+\.?")
_KNOCK_TIMEOUT = 0.5  # s: loopback answers or refuses at once
_IP_ENDPOINT = re.compile(r"^(?:tcp|tls|quic|ws)/\[?([^\]\s]+?)\]?:(\d+)(?:[?#].*)?$")


def clean(message: str) -> str:
    """A Zenoh message without the Rust source places it carries (``at /...rs:447.``)."""
    return _RUST_PLACE.sub("", message).strip()


def port_answers(endpoint: str) -> bool | None:
    """Whether something accepts TCP connections at ``endpoint``'s host and port
    (None: not an IP endpoint, e.g. a unix socket)."""
    match = _IP_ENDPOINT.match(endpoint)
    if match is None:
        return None
    host, port = match.group(1), int(match.group(2))
    try:
        with socket.create_connection((host, port), timeout=_KNOCK_TIMEOUT):
            return True
    except OSError:
        return False


def open_failure(
    endpoints: list[str],
    error: str,
    took: float,
    handshake_limit: float,
    tls: TlsFiles | None = None,
) -> str:
    """What went wrong opening a session that was to connect to ``endpoints`` (a TLS
    endpoint's refusal is explained by :func:`tls_problem`, given the session's files)."""
    if not endpoints:
        return clean(error)
    reasons = []
    for endpoint in endpoints:
        answers = port_answers(endpoint)
        if answers is None:
            reasons.append(f"cannot connect to {endpoint}: {clean(error)}")
        elif not answers:
            reasons.append(f"no router at {endpoint}")
        elif took >= 0.9 * handshake_limit:
            reasons.append(
                f"the router at {endpoint} did not complete the session handshake "
                f"within {handshake_limit:.1f} s (hung or overloaded?)"
            )
        elif tls is not None and (problem := tls_problem(endpoint, tls)) is not None:
            reasons.append(problem)
        else:
            reasons.append(
                f"the router at {endpoint} refused the session: check user and password "
                "(transport/auth/usrpwd in the config file)"
            )
    return "; ".join(reasons)
