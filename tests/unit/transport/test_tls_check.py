"""A refused TLS session explained: which side refused, and why (a real ssl server)."""

from __future__ import annotations

import socket
import ssl
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from aiobt.deploy.certs import CertPlan, write_certs
from aiobt.transport.diagnose import open_failure
from aiobt.transport.tls_check import TlsFiles, tls_problem

ZENOH_ERROR = "Unable to connect to any of [Single(tls/127.0.0.1:1)]!"


def files(directory: Path, name: str, ca: Path | None = None) -> TlsFiles:
    return TlsFiles(
        root_ca=str(ca or directory / "ca.pem"),
        certificate=str(directory / f"{name}.pem"),
        private_key=str(directory / f"{name}-key.pem"),
    )


@pytest.fixture(scope="module")
def deployments(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    ours, theirs = tmp_path_factory.mktemp("ours"), tmp_path_factory.mktemp("theirs")
    write_certs(ours, CertPlan())
    write_certs(theirs, CertPlan())
    return ours, theirs


@pytest.fixture
def router(deployments: tuple[Path, Path]) -> Iterator[str]:
    yield from _tls_server(deployments[0], "127.0.0.1")


@pytest.fixture
def router_on_127_0_0_2(deployments: tuple[Path, Path]) -> Iterator[str]:
    yield from _tls_server(deployments[0], "127.0.0.2")


def _tls_server(ours: Path, host: str) -> Iterator[str]:
    """A mutual-TLS server with router-robot's certificate, requiring our CA's clients."""
    context = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH, cafile=str(ours / "ca.pem"))
    context.verify_mode = ssl.CERT_REQUIRED
    context.load_cert_chain(ours / "router-robot.pem", ours / "router-robot-key.pem")
    server = socket.create_server((host, 0))
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.1)
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except TimeoutError:
                continue
            try:
                with context.wrap_socket(conn, server_side=True) as tls:
                    tls.settimeout(2.0)
                    tls.recv(1)
            except (ssl.SSLError, OSError):
                pass

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"tls/{host}:{server.getsockname()[1]}"
    stop.set()
    thread.join(5.0)
    server.close()


def test_a_good_certificate_is_no_tls_problem(deployments: tuple[Path, Path], router: str) -> None:
    ours, _ = deployments
    assert tls_problem(router, files(ours, "web")) is None


def test_trusting_another_ca_is_named(deployments: tuple[Path, Path], router: str) -> None:
    _, theirs = deployments
    problem = tls_problem(router, files(theirs, "web"))
    assert problem is not None
    assert problem.startswith(f"the router at {router} has a certificate that ")
    assert "this session trusts another CA than the router's" in problem


def test_a_certificate_of_another_ca_is_named(deployments: tuple[Path, Path], router: str) -> None:
    ours, theirs = deployments
    problem = tls_problem(router, files(theirs, "web", ca=ours / "ca.pem"))
    assert problem is not None
    assert problem.startswith(f"the router at {router} refused this session's certificate ")
    assert str(theirs / "web.pem") in problem


def test_no_certificate_is_named(deployments: tuple[Path, Path], router: str) -> None:
    ours, _ = deployments
    problem = tls_problem(router, TlsFiles(root_ca=str(ours / "ca.pem")))
    assert problem is not None
    assert "it requires a client certificate" in problem


def test_a_router_dialled_at_an_address_its_certificate_does_not_name(
    deployments: tuple[Path, Path], router_on_127_0_0_2: str
) -> None:
    ours, _ = deployments  # the certificate names 127.0.0.1, not 127.0.0.2
    problem = tls_problem(router_on_127_0_0_2, files(ours, "web"))
    assert problem is not None
    assert "does not name that address" in problem
    assert "aiobt certs --host NAME=ADDRESS" in problem


def test_open_failure_uses_it_for_tls_endpoints_only(
    deployments: tuple[Path, Path], router: str
) -> None:
    _, theirs = deployments
    message = open_failure([router], ZENOH_ERROR, 0.01, 2.0, files(theirs, "web"))
    assert "trusts another CA" in message
    assert tls_problem("tcp/127.0.0.1:7447", files(theirs, "web")) is None
