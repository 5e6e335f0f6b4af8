"""aiobt certs: a CA, certificates that chain to it under the names the ACL file uses."""

from __future__ import annotations

import json
import stat
from pathlib import Path

import pytest
from cryptography import x509
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.hazmat.primitives.serialization import load_pem_private_key
from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

from aiobt.cli.main import main
from aiobt.deploy.certs import (
    SERVICES,
    CertPlan,
    CertsError,
    cert_path,
    key_path,
    parse_host,
    write_certs,
)
from aiobt.system import catalog

EXPECTED = {*SERVICES, "router-robot", "router-base"}


def _cert(directory: Path, name: str) -> x509.Certificate:
    return x509.load_pem_x509_certificate(cert_path(directory, name).read_bytes())


def _common_name(cert: x509.Certificate) -> str:
    return str(cert.subject.get_attributes_for_oid(NameOID.COMMON_NAME)[0].value)


def _alt_names(cert: x509.Certificate) -> list[str]:
    san = cert.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    return [str(n.value) for n in san]


def test_every_certificate_chains_to_the_ca_under_its_name(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    ca = _cert(tmp_path, "ca")
    assert ca.extensions.get_extension_for_class(x509.BasicConstraints).value.ca
    for name in EXPECTED:
        cert = _cert(tmp_path, name)
        assert _common_name(cert) == name
        cert.verify_directly_issued_by(ca)  # raises if the signature or issuer is wrong
        assert not cert.extensions.get_extension_for_class(x509.BasicConstraints).value.ca
        usages = cert.extensions.get_extension_for_class(x509.ExtendedKeyUsage).value
        assert {ExtendedKeyUsageOID.CLIENT_AUTH, ExtendedKeyUsageOID.SERVER_AUTH} <= set(usages)


def test_the_ca_of_another_deployment_does_not_sign_these(tmp_path: Path) -> None:
    write_certs(tmp_path / "a", CertPlan())
    write_certs(tmp_path / "b", CertPlan())
    other_ca = _cert(tmp_path / "b", "ca")
    assert other_ca.subject != _cert(tmp_path / "a", "ca").subject
    with pytest.raises(ValueError, match=r"[Ii]ssuer"):
        _cert(tmp_path / "a", "web").verify_directly_issued_by(other_ca)


def test_keys_are_private_and_match_their_certificates(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    for name in [*EXPECTED, "ca"]:
        mode = stat.S_IMODE(key_path(tmp_path, name).stat().st_mode)
        assert mode == 0o600, (name, oct(mode))
        key = load_pem_private_key(key_path(tmp_path, name).read_bytes(), None)
        assert isinstance(key, ec.EllipticCurvePrivateKey)
        assert key.public_key() == _cert(tmp_path, name).public_key()


def test_a_router_is_named_for_its_host_and_the_addresses_it_is_dialled_at(
    tmp_path: Path,
) -> None:
    plan = CertPlan(hosts=dict([parse_host("base=198.18.0.2,base.lan")]))
    write_certs(tmp_path, plan)
    names = _alt_names(_cert(tmp_path, "router-base"))
    assert names == ["router-base", "localhost", "127.0.0.1", "::1", "198.18.0.2", "base.lan"]
    assert _alt_names(_cert(tmp_path, "web")) == ["web"]
    assert not cert_path(tmp_path, "router-robot").exists()


def test_refuses_to_overwrite_without_force(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    before = cert_path(tmp_path, "ca").read_bytes()
    with pytest.raises(CertsError, match="exists: pass --force"):
        write_certs(tmp_path, CertPlan())
    assert cert_path(tmp_path, "ca").read_bytes() == before
    write_certs(tmp_path, CertPlan(), force=True)
    assert cert_path(tmp_path, "ca").read_bytes() != before


def test_renew_keeps_the_ca_and_issues_new_certificates(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    ca_before, web_before = cert_path(tmp_path, "ca").read_bytes(), _cert(tmp_path, "web")
    write_certs(tmp_path, CertPlan(), renew=True)
    assert cert_path(tmp_path, "ca").read_bytes() == ca_before
    web = _cert(tmp_path, "web")
    assert web.serial_number != web_before.serial_number
    web.verify_directly_issued_by(_cert(tmp_path, "ca"))


def test_renew_without_a_ca_says_so(tmp_path: Path) -> None:
    with pytest.raises(CertsError, match="cannot read the CA in"):
        write_certs(tmp_path, CertPlan(), renew=True)


@pytest.mark.parametrize("bad", ["", "=1.2.3.4", "ro bot", "a/b=1.2.3.4"])
def test_a_bad_host_is_named(bad: str) -> None:
    with pytest.raises(CertsError, match="--host"):
        parse_host(bad)


def test_the_command_writes_certificates_and_each_identity_s_zenoh_config(
    tmp_path: Path,
) -> None:
    directory = tmp_path / "certs"
    assert main(["certs", str(directory), "--host", "robot=198.18.0.1"]) == 0
    web = json.loads(_without_comment(directory / "web.json5"))
    assert web["transport"]["link"]["tls"] == {
        "root_ca_certificate": str(directory / "ca.pem"),
        "enable_mtls": True,
        "connect_certificate": str(directory / "web.pem"),
        "connect_private_key": str(directory / "web-key.pem"),
    }
    router = json.loads(_without_comment(directory / "router-robot.json5"))
    assert router["mode"] == "router"
    assert router["transport"]["link"]["tls"]["listen_certificate"] == str(
        directory / "router-robot.pem"
    )
    assert main(["certs", str(directory)]) == 2  # exists: refused


def _without_comment(path: Path) -> str:
    return "".join(line for line in path.read_text().splitlines() if not line.startswith("//"))


def test_seen_at_names_the_files_where_the_containers_mount_them(tmp_path: Path) -> None:
    directory = tmp_path / "compose-certs"
    args = ["certs", str(directory), "--host", "compose=router", "--seen-at", "/certs"]
    assert main(args) == 0
    router = json.loads(_without_comment(directory / "router-compose.json5"))
    assert router["transport"]["link"]["tls"]["listen_certificate"] == "/certs/router-compose.pem"
    planner = json.loads(_without_comment(directory / "planner.json5"))
    assert planner["transport"]["link"]["tls"]["connect_private_key"] == "/certs/planner-key.pem"
    assert "router" in _alt_names(_cert(directory, "router-compose"))
    assert main(["certs", str(tmp_path / "other"), "--seen-at", "certs"]) == 2  # not absolute


def test_a_certificate_for_every_service_of_the_catalog(tmp_path: Path) -> None:
    write_certs(tmp_path, CertPlan())
    for spec in catalog.SERVICES:
        assert _common_name(_cert(tmp_path, spec.name)) == spec.name
