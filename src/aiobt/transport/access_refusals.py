"""Who a mutual-TLS router with access control refused, and for what, from Zenoh's log.

Zenoh (Rust) says it only in its log, in these lines (1.10):

- ``zenoh_link_tls::unicast`` (debug): ``Accepted TLS connection on A: PEER. Common
  Name: web.``: a session's certificate was good; which name it carries;
- the same module (warn) when the TLS handshake failed: ``invalid peer
  certificate: UnknownIssuer`` (signed by another CA), ``peer sent no
  certificates``, ``received fatal alert: UnknownCA`` (the client did not trust
  this router's certificate). Zenoh does not say the peer's address there;
- ``zenoh::net::routing::interceptor::access_control`` (trace): ``ZID on
  Interface(lo)+CertCommonName(web)+... is unauthorized to Put (ingress) on
  robot/cmd_vel`` for a message on a key not declared, and for each kind of message
  when a declared key's permissions are cached (after ``ACL (ingress): caching
  permissions for `KEY```: not reported, nothing was sent yet), then ``Using cached
  result: ZID is unauthorized to ...`` for every message on a declared key; (info)
  ``ZID did not match any configured ACL subject``.

:class:`AccessRefusals` turns them into one warning per refusal, the first of a
kind at once and then one counted line at most every ``interval`` seconds.
"""

from __future__ import annotations

import logging
import re
import time
from collections.abc import Callable
from dataclasses import dataclass, field

# the lines to turn on in Zenoh's log (the access-control module at trace: one line
# per message the router routes, read and dropped here unless it is a denial)
TLS_LOG_FILTER = "zenoh_link_tls::unicast=debug"
ACL_LOG_FILTER = "zenoh::net::routing::interceptor::access_control=trace"

_ACCEPTED = re.compile(r"Accepted TLS connection on \S+: (\S+)\. Common Name: ([^.]*)\.")
_BAD_CERT = re.compile(r"zenoh_link_tls::unicast: invalid peer certificate: (\w+)")
_NO_CERT = re.compile(r"zenoh_link_tls::unicast: peer sent no certificates")
_ALERT = re.compile(r"zenoh_link_tls::unicast: received fatal alert: (\w+)")
_DECIDED = re.compile(
    r"access_control: (\w+) on \S*CertCommonName\(([^)]*)\)\S* is (un)?authorized to (.+?) "
    r"\((ingress|egress)\) on (\S+)"
)
_DENIED_CACHED = re.compile(
    r"access_control: Using cached result: (\w+) is unauthorized to (.+?) "
    r"\((ingress|egress)\) on (\S+)"
)
_NO_SUBJECT = re.compile(r"access_control: (\w+) did not match any configured ACL subject")
_CACHING = re.compile(
    r"access_control: ACL \((ingress|egress)\): caching permissions for `([^`]*)`"
)

_BAD_CERT_WORDS = {
    "UnknownIssuer": "not signed by this deployment's CA",
    "BadSignature": "not signed by this deployment's CA",
    "Expired": "expired",
    "NotValidYet": "not valid yet (a host's clock?)",
    "Revoked": "revoked",
}


@dataclass(slots=True)
class _Kind:
    said_at: float = -float("inf")
    unsaid: int = 0
    total: int = 0


@dataclass(slots=True)
class AccessRefusals:
    """Reads Zenoh's TLS and access-control lines; logs each refusal, rate-limited."""

    logger: logging.Logger
    interval: float = 10.0
    clock: Callable[[], float] = time.monotonic
    names: dict[str, str] = field(default_factory=dict)  # session id -> certificate name
    kinds: dict[tuple[str, ...], _Kind] = field(default_factory=dict)
    _last_peer: tuple[str, str] = ("an unknown address", "")
    # a key's permissions being cached (flow, key): Zenoh then logs its verdict on each
    # kind of message for that key once, sent or not: not reported; the fill ends at a
    # kind seen twice or any other line
    _filling: tuple[str, str] | None = None
    _filled: set[str] = field(default_factory=set)

    @property
    def total(self) -> int:
        return sum(kind.total for kind in self.kinds.values())

    def on_line(self, line: str) -> bool:
        """Note ``line``; True if it was one of these (so it is not passed on)."""
        if "access_control" not in line and "zenoh_link_tls" not in line:
            return False
        if "Using cached result" in line and " is authorized " in line:
            return True  # the steady stream, a line per message routed: dropped at once
        if accepted := _ACCEPTED.search(line):
            self._last_peer = (accepted.group(1), accepted.group(2))
        elif caching := _CACHING.search(line):
            self._filling, self._filled = (caching.group(1), caching.group(2)), set()
        elif decided := _DECIDED.search(line):
            zid, name, refused, what, flow, key = decided.groups()
            self.names[zid] = name
            if self._filling == (flow, key) and what not in self._filled:
                self._filled.add(what)
            else:
                self._filling = None
                if refused:
                    self._denied(zid, what, flow, key)
        elif cached := _DENIED_CACHED.search(line):
            self._denied(*cached.groups())
        elif unknown := _NO_SUBJECT.search(line):
            peer, name = self._last_peer
            self._say(
                ("unknown", name),
                "certificate %r (session %s, from %s) is named nowhere in the access-control "
                "file: everything it sends is denied",
                name,
                unknown.group(1),
                peer,
            )
        else:
            # an unknown Zenoh warning is passed on; its debug and trace chatter is not
            return self._tls_refused(line) or ("WARN" not in line and "ERROR" not in line)
        return True

    def _denied(self, zid: str, what: str, flow: str, key: str) -> None:
        name = self.names.get(zid, "an unnamed certificate")
        direction = "from" if flow == "ingress" else "to"
        self._say(
            ("denied", zid, what, key),
            "denied %s %s %s (session %s) on %s",
            what,
            direction,
            name,
            zid,
            key,
        )

    def _tls_refused(self, line: str) -> bool:
        if bad := _BAD_CERT.search(line):
            reason = bad.group(1)
            why = _BAD_CERT_WORDS.get(reason, "not accepted")
            self._say(
                ("tls", reason), "refused a TLS session: its certificate is %s (%s)", why, reason
            )
        elif _NO_CERT.search(line):
            self._say(
                ("tls", "none"),
                "refused a TLS session: it presented no certificate (this router requires "
                "mutual TLS: enable_mtls, connect_certificate, connect_private_key)",
            )
        elif alert := _ALERT.search(line):
            self._say(
                ("tls", alert.group(1)),
                "a TLS client refused this router's certificate (%s): it trusts another CA, "
                "or dialled an address the certificate does not name",
                alert.group(1),
            )
        else:
            return False
        return True

    def _say(self, kind_key: tuple[str, ...], message: str, *args: object) -> None:
        kind = self.kinds.setdefault(kind_key, _Kind())
        kind.total += 1
        now = self.clock()
        if now - kind.said_at < self.interval:
            kind.unsaid += 1
            return
        if kind.unsaid:
            message += " (%d more since the last report)"
            args = (*args, kind.unsaid)
        self.logger.warning(message, *args)
        kind.said_at, kind.unsaid = now, 0
