"""Bus settings: the shared command-line flags, a Zenoh config file, and defaults.

Precedence: a Zenoh config file (``--config`` or ``ZENOH_CONFIG``) first, then
the explicit flags on top; ``AIOBT_ZENOH_USER`` / ``AIOBT_ZENOH_PASSWORD`` in the
environment give the credentials for a router that checks them. Services
default to ``client`` mode connecting to a router on ``tcp/127.0.0.1:7447``,
with a 1000 ms lease so a hung process is noticed within about a second.
"""

from __future__ import annotations

import argparse
import json
import os
from dataclasses import dataclass, field
from typing import Literal, cast

import zenoh

from aiobt.transport.diagnose import clean
from aiobt.transport.keys import check_name

Mode = Literal["client", "peer", "router"]
DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
DEFAULT_NAMESPACE = "robot"
DEFAULT_MAX_PAYLOAD = 16 * 1024 * 1024
OPEN_TIMEOUT_MS = 2000  # a link handshake (Zenoh's default, 10 s, unless a file sets one)
OPEN_TIMEOUT_KEY = "transport/unicast/open_timeout"
_ZENOH_OPEN_TIMEOUT_MS = 10000
SHARED_MEMORY_KEY = "transport/shared_memory/enabled"
# where a router or peer listens unless a flag or the config file says otherwise
# (Zenoh's own default is every interface: tcp/[::]:7447, tcp/[::]:0)
LOOPBACK_LISTEN = {"router": DEFAULT_ROUTER, "peer": "tcp/127.0.0.1:0"}


class BusConfigError(ValueError):
    """A bad bus setting or Zenoh config file; the message names the file/flag and field."""


@dataclass(slots=True, frozen=True)
class BusSettings:
    mode: Mode | None = None
    connect: tuple[str, ...] = ()
    listen: tuple[str, ...] = ()
    namespace: str = DEFAULT_NAMESPACE
    config_file: str | None = None
    lease_ms: int = 1000
    connect_timeout: float | None = None
    max_payload: int = DEFAULT_MAX_PAYLOAD
    extra: dict[str, object] = field(default_factory=dict)

    def __post_init__(self) -> None:
        try:
            check_name(self.namespace, "--namespace")
        except ValueError as exc:
            raise BusConfigError(str(exc)) from None
        if self.mode not in (None, "client", "peer", "router"):
            raise BusConfigError(f"--mode must be client, peer or router, got {self.mode!r}")
        if self.lease_ms < 100:
            raise BusConfigError(f"--lease-ms must be >= 100, got {self.lease_ms}")
        if self.max_payload <= 0:
            raise BusConfigError(f"max_payload must be > 0, got {self.max_payload}")

    @classmethod
    def from_args(cls, args: argparse.Namespace) -> BusSettings:
        """Settings from the flags added by :func:`add_bus_arguments`."""
        return cls(
            mode=cast("Mode | None", args.mode),
            connect=tuple(args.connect or ()),
            listen=tuple(args.listen or ()),
            namespace=args.namespace,
            config_file=args.config,
            lease_ms=args.lease_ms,
            connect_timeout=args.connect_timeout,
        )

    @property
    def effective_config_file(self) -> str | None:
        return self.config_file or os.environ.get("ZENOH_CONFIG") or None

    def zenoh_config(self) -> zenoh.Config:
        """The Zenoh config: the file if any, then these settings on top.

        What the file leaves unset gets aiobt's defaults, not Zenoh's (which would
        make a multicast-scouting peer, and run a service whose credentials the
        router refuses unconnected instead of failing):
        - mode ``client``; a client (not scouting) connects to ``DEFAULT_ROUTER``;
        - multicast scouting off;
        - a peer told where to connect fails to open when it cannot (as a client
          does), so it is retried and ``--connect-timeout`` applies;
        - a link handshake gives up after 2 s, not 10 s, so a hung router neither
          holds the event loop nor overruns ``--connect-timeout`` for long;
        - a router or peer listens on loopback only (``LOOPBACK_LISTEN``), not on
          every interface: listening beyond it takes ``--listen`` or a file's
          ``listen/endpoints``;
        - shared memory off (unless the file says anything about ``shared_memory``):
          Zenoh's default copies every message over 3 KB between processes of one
          host into shared memory, and sets that up on a process's first two such
          messages (a 16 MB pool, mapped and locked in memory, then a segment and
          watchdog threads): each of those sends blocked 10-30 ms, and a plan or a
          path arrived that much late (``bench/transport/first_large.py``).
        """
        config = self._base_config()
        mode = self.mode or ("client" if _unset(config, "mode") else None)
        _insert(config, "mode", mode)
        mode = mode or json.loads(config.get_json("mode"))
        if _unset(config, "scouting/multicast/enabled"):
            _insert(config, "scouting/multicast/enabled", False)
        scouting = json.loads(config.get_json("scouting/multicast/enabled")) is True
        connect = self.connect
        if not connect and mode == "client" and not scouting and not _endpoints_for(config, mode):
            connect = (DEFAULT_ROUTER,)
        _insert(config, "connect/endpoints", list(connect) or None)
        connects = bool(_endpoints_for(config, mode))
        if mode == "peer" and connects and _unset(config, "connect/exit_on_failure"):
            _insert(config, "connect/exit_on_failure", True)
            if _unset(config, "connect/timeout_ms"):
                _insert(config, "connect/timeout_ms", 0)  # one try per open: we retry
        _insert(config, "listen/endpoints", list(self.listen) or None)
        if mode in LOOPBACK_LISTEN and _listens_by_zenoh_default(config):
            _insert(config, "listen/endpoints", [LOOPBACK_LISTEN[mode]])
        _insert(config, "transport/link/tx/lease", self.lease_ms)
        if json.loads(config.get_json(OPEN_TIMEOUT_KEY)) == _ZENOH_OPEN_TIMEOUT_MS:
            _insert(config, OPEN_TIMEOUT_KEY, OPEN_TIMEOUT_MS)
        _insert(config, "timestamping/enabled", True)  # needed by latched (cached) publishers
        if not self._file_mentions("shared_memory"):
            _insert(config, SHARED_MEMORY_KEY, False)
        _insert_credentials(config)
        for key, value in self.extra.items():
            _insert(config, key, value)
        return config

    def _file_mentions(self, word: str) -> bool:
        """Whether the config file's text names ``word`` (a default it may have set
        to Zenoh's own value, which the parsed config cannot tell from unset)."""
        path = self.effective_config_file
        if not path:
            return False
        with open(path, encoding="utf-8", errors="replace") as file:
            return word in file.read()

    def _base_config(self) -> zenoh.Config:
        path = self.effective_config_file
        if not path:
            return zenoh.Config()
        if not os.path.isfile(path):
            raise BusConfigError(f"Zenoh config file {path}: no such file")
        try:
            return zenoh.Config.from_file(path)
        except zenoh.ZError as exc:
            raise BusConfigError(f"Zenoh config file {path}: {clean(str(exc))}") from None


USER_ENV, PASSWORD_ENV = "AIOBT_ZENOH_USER", "AIOBT_ZENOH_PASSWORD"


def _insert_credentials(config: zenoh.Config) -> None:
    """User/password for a router that checks them, from the environment (an env file in
    docker-compose), so no image or config file holds them; both or neither."""
    user, password = os.environ.get(USER_ENV), os.environ.get(PASSWORD_ENV)
    if bool(user) != bool(password):
        raise BusConfigError(f"set both {USER_ENV} and {PASSWORD_ENV}, or neither")
    if user and password:
        _insert(config, "transport/auth/usrpwd/user", user)
        _insert(config, "transport/auth/usrpwd/password", password)


def _endpoints_for(config: zenoh.Config, mode: str, key: str = "connect/endpoints") -> list[str]:
    """``connect/endpoints`` (or ``key``) for ``mode``: a list, or a per-mode dict
    ({router: [...]})."""
    endpoints = json.loads(config.get_json(key)) or []
    return list(endpoints.get(mode, [])) if isinstance(endpoints, dict) else list(endpoints)


def listen_endpoints(config: zenoh.Config) -> list[str]:
    """Where a session opened with ``config`` listens (a client: nowhere)."""
    return _endpoints_for(config, _mode_of(config), "listen/endpoints")


def connect_endpoints(config: zenoh.Config) -> list[str]:
    """Where a session opened with ``config`` connects."""
    return _endpoints_for(config, _mode_of(config))


def _mode_of(config: zenoh.Config) -> str:
    return str(json.loads(config.get_json("mode")) or "peer")  # Zenoh's default mode


def _listens_by_zenoh_default(config: zenoh.Config) -> bool:
    """Whether ``listen/endpoints`` is still Zenoh's default (every interface): neither
    a file nor a flag named an endpoint."""
    return json.loads(config.get_json("listen/endpoints")) == json.loads(
        zenoh.Config().get_json("listen/endpoints")
    ) or _unset(config, "listen/endpoints")


def _unset(config: zenoh.Config, key: str) -> bool:
    """Whether ``key`` is null or empty in ``config`` (a config file did not set it)."""
    return json.loads(config.get_json(key)) in (None, [], {})


def _insert(config: zenoh.Config, key: str, value: object) -> None:
    if value is None:
        return
    try:
        config.insert_json5(key, json.dumps(value))
    except zenoh.ZError as exc:
        raise BusConfigError(f"Zenoh config field {key}={value!r}: {clean(str(exc))}") from None


def add_bus_arguments(parser: argparse.ArgumentParser) -> None:
    """The shared flags: --connect --listen --mode --config --namespace --lease-ms."""
    group = parser.add_argument_group("Zenoh bus")
    group.add_argument(
        "-e",
        "--connect",
        action="append",
        metavar="ENDPOINT",
        help=f"endpoint to connect to, repeatable (client default: {DEFAULT_ROUTER})",
    )
    group.add_argument(
        "-l",
        "--listen",
        action="append",
        metavar="ENDPOINT",
        help="endpoint to listen on, repeatable (peer default: tcp/127.0.0.1:0, loopback "
        "only; e.g. tcp/0.0.0.0:7447 for every interface)",
    )
    group.add_argument(
        "-m",
        "--mode",
        choices=("client", "peer", "router"),
        default=None,
        help="Zenoh session mode (default: client, or the config file's)",
    )
    group.add_argument(
        "-c",
        "--config",
        metavar="FILE",
        default=None,
        help="Zenoh JSON5 config file (default: $ZENOH_CONFIG); the flags override it",
    )
    group.add_argument(
        "-n",
        "--namespace",
        default=os.environ.get("AIOBT_NAMESPACE", DEFAULT_NAMESPACE),
        help="robot namespace, the first chunk of every key (default: %(default)s)",
    )
    group.add_argument(
        "--lease-ms",
        type=int,
        default=1000,
        help="Zenoh link lease: how fast a hung peer is noticed (default: %(default)s ms)",
    )
    group.add_argument(
        "--connect-timeout",
        type=float,
        default=None,
        metavar="SECONDS",
        help="give up if the router is not reachable in time (default: retry forever)",
    )
