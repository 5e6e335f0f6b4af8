"""The router's TLS refusals and access-control denials, from Zenoh's own log lines."""

from __future__ import annotations

import logging

import pytest

from aiobt.transport.access_refusals import AccessRefusals
from aiobt.transport.refusals import Refusals

ZID = "a630ef8eee054ff38d3b29b62c99b6a5"
ACL = "zenoh::net::routing::interceptor::access_control"
ACCEPTED = (
    "2026-11-28T22:47:07.636109Z DEBUG acc-0 ThreadId(06) zenoh_link_tls::unicast: Accepted "
    "TLS connection on 127.0.0.1:17447: 127.0.0.1:36606. Common Name: web."
)
DENIED = (
    f"2026-11-28T22:47:07.937679Z TRACE  rx-1 ThreadId(10) {ACL}: {ZID} on Interface(lo)+"
    f"CertCommonName(web)+Transport(Tls)+{ZID} is unauthorized to Put (ingress) on robot/cmd_vel"
)
CACHED = (
    f"2026-11-28T22:47:08Z TRACE rx-1 ThreadId(10) {ACL}: Using cached result: {ZID} is "
    "unauthorized to Put (ingress) on robot/cmd_vel"
)
ALLOWED = DENIED.replace("unauthorized", "authorized").replace("Put", "Declare Subscriber")


class FakeClock:
    now = 0.0

    def __call__(self) -> float:
        return self.now


def test_a_denial_names_the_certificate_the_message_and_the_key_rate_limited(
    caplog: pytest.LogCaptureFixture,
) -> None:
    clock = FakeClock()
    refusals = AccessRefusals(logging.getLogger("test.acl"), interval=10.0, clock=clock)
    with caplog.at_level(logging.WARNING, logger="test.acl"):
        assert refusals.on_line(ACCEPTED)
        assert refusals.on_line(ALLOWED)
        assert refusals.on_line(DENIED)
        for _ in range(30):  # a teleop loop of a viewer at 20 Hz
            assert refusals.on_line(CACHED)
        clock.now = 10.5
        refusals.on_line(CACHED)
    assert [r.getMessage() for r in caplog.records] == [
        f"denied Put from web (session {ZID}) on robot/cmd_vel",
        f"denied Put from web (session {ZID}) on robot/cmd_vel (30 more since the last report)",
    ]
    assert refusals.total == 32


def test_the_verdicts_logged_while_a_key_s_permissions_are_cached_are_not_reported(
    caplog: pytest.LogCaptureFixture,
) -> None:
    """Zenoh logs a verdict on every kind of message when it caches a declared key's
    permissions, though none was sent: those are not denials; a real put after is."""
    refusals = AccessRefusals(logging.getLogger("test.acl"))
    caching = f"2026-11-28T22:55:46Z TRACE rx-1 {ACL}: ACL (ingress): caching permissions for "
    kinds = ["Query", "Reply", "Put", "Delete", "Declare/Undeclare Subscriber"]
    with caplog.at_level(logging.WARNING, logger="test.acl"):
        refusals.on_line(caching + "`robot/cmd_vel` ...")
        for kind in kinds:
            assert refusals.on_line(DENIED.replace("Put", kind))
        assert not caplog.records
        refusals.on_line(DENIED)  # Put again: a message, not the fill
    assert [r.getMessage() for r in caplog.records] == [
        f"denied Put from web (session {ZID}) on robot/cmd_vel"
    ]


def test_tls_refusals_say_which_side_refused_and_why(caplog: pytest.LogCaptureFixture) -> None:
    refusals = AccessRefusals(logging.getLogger("test.acl"))
    tls = "2026-11-28T22:47:11Z  WARN acc-0 ThreadId(06) zenoh_link_tls::unicast: "
    hint = ". Hint: increase the system open file limit."
    with caplog.at_level(logging.WARNING, logger="test.acl"):
        assert refusals.on_line(tls + "invalid peer certificate: UnknownIssuer" + hint)
        assert refusals.on_line(tls + "peer sent no certificates" + hint)
        assert refusals.on_line(tls + "received fatal alert: UnknownCA" + hint)
        assert not refusals.on_line(tls + "some other trouble" + hint)  # passed on as is
    messages = [r.getMessage() for r in caplog.records]
    assert messages == [
        "refused a TLS session: its certificate is not signed by this deployment's CA "
        "(UnknownIssuer)",
        "refused a TLS session: it presented no certificate (this router requires mutual "
        "TLS: enable_mtls, connect_certificate, connect_private_key)",
        "a TLS client refused this router's certificate (UnknownCA): it trusts another CA, "
        "or dialled an address the certificate does not name",
    ]


def test_a_certificate_named_nowhere_is_reported_with_its_name_and_address(
    caplog: pytest.LogCaptureFixture,
) -> None:
    refusals = AccessRefusals(logging.getLogger("test.acl"))
    unmatched = (
        f"2026-11-28T22:47:08Z  INFO rx-1 {ACL}: {ZID} did not match any configured ACL "
        "subject. Default permission `Deny` will be applied on all messages"
    )
    with caplog.at_level(logging.WARNING, logger="test.acl"):
        refusals.on_line(ACCEPTED.replace("Common Name: web.", "Common Name: intruder."))
        refusals.on_line(unmatched)
    assert [r.getMessage() for r in caplog.records] == [
        f"certificate 'intruder' (session {ZID}, from 127.0.0.1:36606) is named nowhere in "
        "the access-control file: everything it sends is denied"
    ]


def test_the_router_s_reader_hands_these_lines_to_it_and_passes_nothing_on() -> None:
    access = AccessRefusals(logging.getLogger("test.acl"))
    refusals = Refusals(logging.getLogger("test.router"), access=access)
    assert refusals.on_line("\x1b[2m" + DENIED + "\x1b[0m\n") is None
    assert access.total == 1
    assert refusals.on_line(ALLOWED) is None
