"""Open failures in words a user can act on, and the router's refused-session lines."""

from __future__ import annotations

import logging
import socket
from collections.abc import Iterator

import pytest

from aiobt.transport.diagnose import clean, open_failure, port_answers
from aiobt.transport.refusals import Refusals

ZENOH_ERROR = (
    "Unable to connect to any of [Single(tcp/127.0.0.1:7447)]!  at /root/.cargo/git/checkouts/"
    "zenoh-9c599d5ef3e0480e/cc83980/zenoh/src/net/runtime/orchestrator.rs:447."
)
ACCEPTED = (
    "\x1b[2m2026-11-25T20:11:16.344728Z\x1b[0m \x1b[34mDEBUG\x1b[0m acc-0 ThreadId(05) "
    "zenoh_link_tcp::unicast: Accepted TCP connection on 127.0.0.1:17449: 127.0.0.1:45014\n"
)


def refused(reason: str, step: str = "OpenSyn") -> str:
    return (
        "2026-11-25T20:11:16.347641Z DEBUG acc-0 ThreadId(05) zenoh_transport::unicast::"
        f"establishment::accept: UsrPwd extension - Recv {step}. {reason}. at /root/.cargo/git/"
        "checkouts/zenoh/io/zenoh-transport/src/unicast/establishment/ext/auth/usrpwd.rs:418.\n"
    )


def test_clean_drops_rust_source_places() -> None:
    assert clean(ZENOH_ERROR) == "Unable to connect to any of [Single(tcp/127.0.0.1:7447)]!"


@pytest.fixture
def listening() -> Iterator[str]:
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen()
        yield f"tcp/127.0.0.1:{server.getsockname()[1]}"


def closed_endpoint() -> str:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return f"tcp/127.0.0.1:{probe.getsockname()[1]}"


def test_open_failure_tells_a_refusal_from_no_router(listening: str) -> None:
    nobody = closed_endpoint()
    assert port_answers(listening) is True
    assert port_answers(nobody) is False
    assert port_answers("unixsock-stream//tmp/zenoh.sock") is None
    refusal = open_failure([listening], ZENOH_ERROR, took=0.01, handshake_limit=2.0)
    assert refusal == (
        f"the router at {listening} refused the session: check user and password "
        "(transport/auth/usrpwd in the config file)"
    )
    assert open_failure([nobody], ZENOH_ERROR, 0.01, 2.0) == f"no router at {nobody}"
    hung = open_failure([listening], ZENOH_ERROR, took=2.0, handshake_limit=2.0)
    assert "did not complete the session handshake within 2.0 s" in hung
    other = open_failure(["unixsock-stream//tmp/z.sock"], ZENOH_ERROR, 0.01, 2.0)
    assert other.startswith("cannot connect to unixsock-stream//tmp/z.sock: Unable to connect")
    assert ".rs" not in other
    assert open_failure([], ZENOH_ERROR, 0.01, 2.0) == clean(ZENOH_ERROR)


class FakeClock:
    now = 0.0

    def __call__(self) -> float:
        return self.now


def test_refused_sessions_are_logged_with_the_peer_rate_limited(
    caplog: pytest.LogCaptureFixture,
) -> None:
    clock = FakeClock()
    refusals = Refusals(logging.getLogger("test.router"), interval=10.0, clock=clock)
    with caplog.at_level(logging.WARNING, logger="test.router"):
        assert refusals.on_line(ACCEPTED) is None
        assert refusals.on_line(refused("Invalid password")) is None
        for _ in range(50):  # a password guesser
            refusals.on_line(ACCEPTED)
            refusals.on_line(refused("Invalid user"))
        clock.now = 11.0
        refusals.on_line(ACCEPTED.replace("45014", "45999"))
        refusals.on_line(refused("Expected extension", "InitSyn"))
    lines = [r.getMessage() for r in caplog.records]
    assert lines == [
        "refused a session from 127.0.0.1:45014: wrong password (UsrPwd authentication)",
        "refused a session from 127.0.0.1:45999: no user and password given "
        "(UsrPwd authentication) (50 more refused since the last report)",
    ]
    assert refusals.total == 52


def test_zenoh_warnings_are_passed_on_cleaned_and_the_rest_kept_back() -> None:
    refusals = Refusals(logging.getLogger("test.router"))
    warning = "2026-11-25T20:11:16Z  WARN ThreadId(01) zenoh::net: link lost at /x/y/z.rs:12."
    assert (
        refusals.on_line(warning) == "2026-11-25T20:11:16Z  WARN ThreadId(01) zenoh::net: link lost"
    )
    assert refusals.on_line("2026-11-25T20:11:16Z DEBUG ThreadId(01) zenoh_link_tcp: other") is None
    everything = Refusals(logging.getLogger("test.router"), forward_all=True)
    assert everything.on_line("2026-11-25T20:11:16Z DEBUG zenoh_link_tcp: other") is not None
