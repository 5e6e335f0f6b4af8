"""Why a router refused a TLS session, found by shaking its hand the same way.

Zenoh says only "Unable to connect to any of [tls/...]" when the TLS handshake fails,
whichever side refused. This module repeats the handshake with Python's ``ssl`` and
the same files (the CA, this session's certificate and key) and says which side
refused and why: the router's certificate is not signed by our CA or does not carry
the address we dialled; or the router refused our certificate (another CA, expired,
none given).
"""

from __future__ import annotations

import json
import re
import socket
import ssl
from dataclasses import dataclass

import zenoh

_TLS_ENDPOINT = re.compile(r"^tls/\[?([^\]\s]+?)\]?:(\d+)(?:[?#].*)?$")
_TIMEOUT = 1.0  # s: a handshake and the router's verdict on our certificate
_PREFIX = "transport/link/tls/"


@dataclass(slots=True, frozen=True)
class TlsFiles:
    root_ca: str | None = None
    certificate: str | None = None
    private_key: str | None = None
    verify_name: bool = True

    @classmethod
    def of(cls, config: zenoh.Config) -> TlsFiles:
        def get(key: str) -> object:
            return json.loads(config.get_json(_PREFIX + key))

        mtls = get("enable_mtls") is True
        return cls(
            root_ca=_str(get("root_ca_certificate")),
            certificate=_str(get("connect_certificate")) if mtls else None,
            private_key=_str(get("connect_private_key")) if mtls else None,
            verify_name=get("verify_name_on_connect") is not False,
        )


def tls_problem(endpoint: str, files: TlsFiles) -> str | None:
    """What is wrong with a TLS session to ``endpoint`` (None: not a tls endpoint, or
    the handshake went through, so the refusal came later)."""
    match = _TLS_ENDPOINT.match(endpoint)
    if match is None:
        return None
    host, port = match.group(1), int(match.group(2))
    try:
        context = _context(files)
    except (OSError, ssl.SSLError) as exc:
        return f"cannot use the TLS files of this session's config: {exc}"
    try:
        with (
            socket.create_connection((host, port), timeout=_TIMEOUT) as raw,
            context.wrap_socket(raw, server_hostname=host) as tls,
        ):
            tls.recv(1)  # TLS 1.3: the router's verdict on our certificate comes now
    except ssl.SSLCertVerificationError as exc:
        return _router_cert_refused(endpoint, files, exc)
    except ssl.SSLError as exc:
        return _our_cert_refused(endpoint, files, exc)
    except (TimeoutError, OSError):
        return None
    return None


def _context(files: TlsFiles) -> ssl.SSLContext:
    context = ssl.create_default_context(ssl.Purpose.SERVER_AUTH, cafile=files.root_ca)
    context.check_hostname = files.verify_name
    if files.certificate and files.private_key:
        context.load_cert_chain(files.certificate, files.private_key)
    return context


def _router_cert_refused(endpoint: str, files: TlsFiles, exc: ssl.SSLCertVerificationError) -> str:
    ca = files.root_ca or "the system's CAs"
    reason = exc.verify_message or str(exc)
    if "mismatch" in reason or "match" in reason:
        return (
            f"the router at {endpoint} has a certificate that does not name that address "
            f"({reason}): make its certificate with `aiobt certs --host NAME=ADDRESS`"
        )
    return (
        f"the router at {endpoint} has a certificate that {ca} does not vouch for "
        f"({reason}): this session trusts another CA than the router's"
    )


def _our_cert_refused(endpoint: str, files: TlsFiles, exc: ssl.SSLError) -> str:
    if not files.certificate:
        return (
            f"the router at {endpoint} refused the TLS session ({exc.reason}): it requires a "
            "client certificate (transport/link/tls: enable_mtls, connect_certificate, "
            "connect_private_key)"
        )
    return (
        f"the router at {endpoint} refused this session's certificate {files.certificate} "
        f"({exc.reason}): it is not signed by the router's CA, or has expired"
    )


def _str(value: object) -> str | None:
    return value if isinstance(value, str) and value else None
