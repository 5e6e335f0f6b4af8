"""A certificate authority and one certificate per service and host, for mutual TLS.

Every Zenoh session of a deployment presents a certificate signed by one CA; the
routers accept only sessions whose certificate chains to it, and the access-control
file (``deploy/access-control.json5``) grants rights by the certificate's common
name. So the common names here are the ones that file names:

- one per service of the catalog (``robot``, ``controller``, ``planner``, ...:
  ``aiobt.system.catalog``), and one per other client: ``web``, ``teleop``,
  ``laptop``, and ``supervisor`` (the session of ``aiobt up`` itself, which only
  watches);
- one per host's router: ``router-<host>`` (``router-robot``, ``router-base``), whose
  subject alternative names are the addresses the other router and the host's own
  services dial (always ``localhost``, ``127.0.0.1`` and ``::1``), since Zenoh checks
  them (``verify_name_on_connect``).

Files in the directory: ``ca.pem`` and ``ca-key.pem``, then ``<name>.pem`` and
``<name>-key.pem`` per name. Keys are ECDSA P-256, written with mode 0600.
"""

from __future__ import annotations

import datetime
import ipaddress
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

from aiobt.system import catalog

# who else has a session: the web view, a person driving by hand, a laptop sending goals,
# and `aiobt up`'s own (it only watches)
CLIENTS = ("web", "teleop", "laptop", "supervisor")
SERVICES = (*catalog.SERVICE_NAMES, *CLIENTS)
"""Every identity but the routers: each service of the catalog, then :data:`CLIENTS`."""
DEFAULT_HOSTS = ("robot", "base")
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")
CA_NAME = "ca"
DEFAULT_DAYS = 365
_CA_DAYS = 3650


class CertsError(ValueError):
    """A bad request for certificates; the message names the file or the name."""


@dataclass(slots=True, frozen=True)
class CertPlan:
    """Which certificates to make: the services' and one router per host (with the
    extra addresses each router is reached at)."""

    services: tuple[str, ...] = SERVICES
    hosts: Mapping[str, tuple[str, ...]] = field(
        default_factory=lambda: dict.fromkeys(DEFAULT_HOSTS, ())
    )
    days: int = DEFAULT_DAYS

    def names(self) -> list[str]:
        return [*self.services, *(router_name(host) for host in self.hosts)]

    def alt_names(self, name: str) -> tuple[str, ...]:
        for host, addresses in self.hosts.items():
            if name == router_name(host):
                return (name, *LOOPBACK_NAMES, *addresses)
        return (name,)


def router_name(host: str) -> str:
    return f"router-{host}"


def parse_host(text: str) -> tuple[str, tuple[str, ...]]:
    """``base=198.18.0.2,base.lan`` -> ("base", ("198.18.0.2", "base.lan"))."""
    host, _, rest = text.partition("=")
    host = host.strip()
    if not host or not host.replace("-", "").replace("_", "").isalnum():
        raise CertsError(f"--host {text!r}: expected NAME or NAME=ADDRESS[,ADDRESS...]")
    addresses = tuple(a.strip() for a in rest.split(",") if a.strip())
    return host, addresses


def key_path(directory: Path, name: str) -> Path:
    return directory / f"{name}-key.pem"


def cert_path(directory: Path, name: str) -> Path:
    return directory / f"{name}.pem"


def write_certs(
    directory: Path, plan: CertPlan, *, force: bool = False, renew: bool = False
) -> list[Path]:
    """Make the CA (or, with ``renew``, reuse the one in ``directory``) and every
    certificate of ``plan``; returns the files written. Refuses to overwrite any
    file unless ``force`` (``renew`` overwrites the certificates, never the CA)."""
    names = plan.names()
    if len(set(names)) != len(names) or CA_NAME in names:
        raise CertsError(f"names must be distinct and not {CA_NAME!r}: {', '.join(names)}")
    targets = [p for n in names for p in (cert_path(directory, n), key_path(directory, n))]
    if not renew:
        targets += [cert_path(directory, CA_NAME), key_path(directory, CA_NAME)]
    existing = [str(p) for p in targets if p.exists()]
    if existing and not (force or renew):
        raise CertsError(f"{existing[0]} exists: pass --force to overwrite ({len(existing)} files)")
    directory.mkdir(parents=True, exist_ok=True)
    if renew:
        ca_key, ca_cert = load_ca(directory)
        written: list[Path] = []
    else:
        ca_key, ca_cert = make_ca(datetime.datetime.now(datetime.UTC))
        written = _write_pair(directory, CA_NAME, ca_key, ca_cert)
    now = datetime.datetime.now(datetime.UTC)
    for name in names:
        key = ec.generate_private_key(ec.SECP256R1())
        cert = issue(ca_key, ca_cert, key.public_key(), name, plan.alt_names(name), now, plan.days)
        written += _write_pair(directory, name, key, cert)
    return written


def load_ca(directory: Path) -> tuple[ec.EllipticCurvePrivateKey, x509.Certificate]:
    """The CA kept in ``directory`` (for renewing the certificates it signs)."""
    try:
        key = serialization.load_pem_private_key(key_path(directory, CA_NAME).read_bytes(), None)
        cert = x509.load_pem_x509_certificate(cert_path(directory, CA_NAME).read_bytes())
    except (OSError, ValueError) as exc:
        raise CertsError(f"cannot read the CA in {directory}: {exc}") from None
    if not isinstance(key, ec.EllipticCurvePrivateKey):
        raise CertsError(f"{key_path(directory, CA_NAME)}: not an ECDSA key")
    return key, cert


def make_ca(now: datetime.datetime) -> tuple[ec.EllipticCurvePrivateKey, x509.Certificate]:
    key = ec.generate_private_key(ec.SECP256R1())
    # a name of its own: a certificate of another deployment's CA is then an unknown
    # issuer, not a bad signature, in the refusal
    unique = x509.random_serial_number() % 16**8
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, f"aiobt CA {unique:08x}")])
    cert = (
        _builder(name, name, key.public_key(), now, _CA_DAYS)
        .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
        .add_extension(_usage(cert_sign=True), critical=True)
        .add_extension(x509.SubjectKeyIdentifier.from_public_key(key.public_key()), critical=False)
        .sign(key, hashes.SHA256())
    )
    return key, cert


def issue(
    ca_key: ec.EllipticCurvePrivateKey,
    ca_cert: x509.Certificate,
    public_key: ec.EllipticCurvePublicKey,
    common_name: str,
    alt_names: Sequence[str],
    now: datetime.datetime,
    days: int,
) -> x509.Certificate:
    """A certificate for ``common_name``, good as both TLS server and client."""
    subject = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)])
    return (
        _builder(subject, ca_cert.subject, public_key, now, days)
        .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True)
        .add_extension(_usage(cert_sign=False), critical=True)
        .add_extension(
            x509.ExtendedKeyUsage(
                [ExtendedKeyUsageOID.SERVER_AUTH, ExtendedKeyUsageOID.CLIENT_AUTH]
            ),
            critical=False,
        )
        .add_extension(x509.SubjectAlternativeName(list(_general_names(alt_names))), critical=False)
        .add_extension(
            x509.AuthorityKeyIdentifier.from_issuer_public_key(ca_key.public_key()), critical=False
        )
        .sign(ca_key, hashes.SHA256())
    )


def _builder(
    subject: x509.Name,
    issuer: x509.Name,
    public_key: ec.EllipticCurvePublicKey,
    now: datetime.datetime,
    days: int,
) -> x509.CertificateBuilder:
    return (
        x509.CertificateBuilder()
        .subject_name(subject)
        .issuer_name(issuer)
        .public_key(public_key)
        .serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(minutes=5))  # hosts' clocks drift
        .not_valid_after(now + datetime.timedelta(days=days))
    )


def _usage(*, cert_sign: bool) -> x509.KeyUsage:
    return x509.KeyUsage(
        digital_signature=not cert_sign,
        content_commitment=False,
        key_encipherment=False,
        data_encipherment=False,
        key_agreement=False,
        key_cert_sign=cert_sign,
        crl_sign=cert_sign,
        encipher_only=False,
        decipher_only=False,
    )


def _general_names(names: Iterable[str]) -> Iterable[x509.GeneralName]:
    for name in dict.fromkeys(names):
        try:
            yield x509.IPAddress(ipaddress.ip_address(name))
        except ValueError:
            yield x509.DNSName(name)


def _write_pair(
    directory: Path, name: str, key: ec.EllipticCurvePrivateKey, cert: x509.Certificate
) -> list[Path]:
    key_file, cert_file = key_path(directory, name), cert_path(directory, name)
    key_bytes = key.private_bytes(
        serialization.Encoding.PEM,
        serialization.PrivateFormat.PKCS8,
        serialization.NoEncryption(),
    )
    _write_private(key_file, key_bytes)
    cert_file.write_bytes(cert.public_bytes(serialization.Encoding.PEM))
    return [cert_file, key_file]


def _write_private(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path``, readable by its owner only from the first byte on."""
    path.unlink(missing_ok=True)
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    with os.fdopen(fd, "wb") as file:
        file.write(data)
