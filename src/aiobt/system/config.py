"""The system's settings: one YAML file for ``aiobt up`` (and the demo).

    namespace: robot          # robot namespace, the first chunk of every key
    world: office             # shipped world (office, small) or a Nav2 map YAML path
    speed: 1.0                # sim time runs this many times faster than the wall
    sim_time: null            # null: on when speed != 1; true/false forces it
    safety_chain: true        # the velocity smoother and the collision monitor run between
                              # the controller/behaviors (on cmd_vel_nav) and the base
    use_composition: false    # true: the two in one process, `aiobt safety_chain` (Nav2's
                              # composition: one bus session); separate with router.certs
    router:
      listen: tcp/127.0.0.1:7447   # where the router listens and services connect
      start: true             # false: use a router that is already running there
      connect: []             # other hosts' routers to join (one host's share of a deployment)
      certs: null             # a directory of `aiobt certs`: mutual TLS for router and services
      host: robot             # ... whose router certificate is router-<host>
      access_control: null    # the router's access-control rules (deploy/access-control.json5)
      args: []                # extra flags of the router it starts
    restart:
      backoff: 0.5            # s before the first restart, doubled per crash ...
      max_backoff: 8.0        # ... up to this
      max_restarts: 5         # crashes within restart.window s before giving up
      window: 60.0
    services:                 # per service: run it or not, and extra flags
      robot:      {enabled: true, args: []}
      localization: {enabled: true, args: []}   # told the world's start (the robot's --start)
      planner:    {enabled: true, args: []}
      controller: {enabled: true, args: []}
      behaviors:  {enabled: true, args: []}
      velocity_smoother: {enabled: true, args: []}   # with safety_chain (the default)
      collision_monitor: {enabled: true, args: []}   # with safety_chain (the default)
      navigator:  {enabled: true, args: []}
      route:      {enabled: false, args: []}   # Nav2's route server: off, as in Nav2
      docking:    {enabled: false, args: []}   # Nav2's docking server: off, as in Nav2

Every key is optional; an unknown key or a value of the wrong type is a
:class:`ConfigError` naming the file and the key.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from aiobt.system.catalog import SAFETY_CHAIN, SERVICE_NAMES, service
from aiobt.transport.keys import check_name

SERVICES = SERVICE_NAMES  # aiobt.system.catalog: the one list
DEFAULT_LISTEN = "tcp/127.0.0.1:7447"


class ConfigError(ValueError):
    """A bad system setting; the message names the file and the key."""


@dataclass(slots=True, frozen=True)
class RouterConfig:
    listen: str = DEFAULT_LISTEN
    start: bool = True
    args: tuple[str, ...] = ()
    connect: tuple[str, ...] = ()
    certs: str | None = None
    host: str = "robot"
    access_control: str | None = None


@dataclass(slots=True, frozen=True)
class RestartConfig:
    backoff: float = 0.5
    max_backoff: float = 8.0
    max_restarts: int = 5
    window: float = 60.0


@dataclass(slots=True, frozen=True)
class ServiceConfig:
    enabled: bool = True
    args: tuple[str, ...] = ()


@dataclass(slots=True, frozen=True)
class SystemConfig:
    namespace: str = "robot"
    world: str = "office"
    speed: float = 1.0
    sim_time: bool | None = None
    safety_chain: bool = True
    use_composition: bool = False
    router: RouterConfig = RouterConfig()
    restart: RestartConfig = RestartConfig()
    services: Mapping[str, ServiceConfig] = field(
        default_factory=lambda: {
            name: ServiceConfig(enabled=service(name).enabled) for name in SERVICES
        }
    )

    @property
    def uses_sim_time(self) -> bool:
        return self.speed != 1.0 if self.sim_time is None else self.sim_time

    def enabled(self) -> list[str]:
        return [
            name
            for name in SERVICES
            if self.services[name].enabled and (self.safety_chain or name not in SAFETY_CHAIN)
        ]


def load_config(
    path: str | Path | None, overrides: Mapping[str, Any] | None = None
) -> SystemConfig:
    """The settings in ``path`` (defaults without one), then ``overrides`` (flags) on top."""
    where = str(path) if path else "defaults"
    data: Any = {}
    if path:
        try:
            data = yaml.safe_load(Path(path).read_text(encoding="utf-8")) or {}
        except OSError as exc:
            raise ConfigError(f"{where}: cannot read: {exc.strerror}") from None
        except yaml.YAMLError as exc:
            raise ConfigError(f"{where}: not valid YAML: {exc}") from None
    if not isinstance(data, dict):
        raise ConfigError(f"{where}: expected a mapping of settings, got {type(data).__name__}")
    return config_from_dict(_merged(data, overrides or {}), where)


def _merged(data: Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """``data`` with the non-None ``overrides`` on top (sections merged key by key)."""
    merged = dict(data)
    for key, value in overrides.items():
        if isinstance(value, Mapping) and isinstance(merged.get(key), Mapping):
            merged[key] = _merged(merged[key], value)
        elif value is not None:
            merged[key] = value
    return merged


def config_from_dict(data: Mapping[str, Any], where: str = "config") -> SystemConfig:
    _check_keys(data, SystemConfig, where, "")
    config = SystemConfig(
        namespace=_typed(data, "namespace", str, "robot", where),
        world=_typed(data, "world", str, "office", where),
        speed=_number(data, "speed", 1.0, where, positive=True),
        sim_time=_typed(data, "sim_time", bool, None, where),
        safety_chain=_typed(data, "safety_chain", bool, True, where),
        use_composition=_typed(data, "use_composition", bool, False, where),
        router=_router(_section(data, "router", where), where),
        restart=_restart(_section(data, "restart", where), where),
        services=_services(_section(data, "services", where), where),
    )
    _check_namespace(config.namespace, where)
    if data.get("use_composition") is True and config.router.certs:  # one certificate
        raise ConfigError(
            f"{where}: use_composition with router.certs: a composed process has one "
            "session and no certificate of its own yet; run the services separately"
        )
    return config


def _router(data: Mapping[str, Any], where: str) -> RouterConfig:
    _check_keys(data, RouterConfig, where, "router.")
    listen = _typed(data, "listen", str, DEFAULT_LISTEN, where, "router.")
    if not listen.startswith(("tcp/", "udp/", "tls/", "quic/", "ws/")):
        raise ConfigError(f"{where}: router.listen must be a Zenoh endpoint like {DEFAULT_LISTEN}")
    start = _typed(data, "start", bool, True, where, "router.")
    certs = _typed(data, "certs", str, None, where, "router.")
    _check_certs(certs, listen, where)
    return RouterConfig(
        listen,
        start,
        _args(data, where, "router."),
        connect=_endpoints(data, "connect", where),
        certs=certs,
        host=_typed(data, "host", str, "robot", where, "router."),
        access_control=_typed(data, "access_control", str, None, where, "router."),
    )


def _check_certs(certs: str | None, listen: str, where: str) -> None:
    if certs is None:
        return
    if not listen.startswith("tls/"):
        raise ConfigError(f"{where}: router.certs needs a tls/ router.listen, got {listen}")
    if not (Path(certs) / "ca.pem").is_file():
        raise ConfigError(
            f"{where}: router.certs {certs}: no ca.pem there (make them: aiobt certs {certs})"
        )


def _endpoints(data: Mapping[str, Any], key: str, where: str) -> tuple[str, ...]:
    value = data.get(key, [])
    value = [value] if isinstance(value, str) else value
    if not isinstance(value, list) or not all(isinstance(e, str) and "/" in e for e in value):
        raise ConfigError(
            f"{where}: router.{key} must be a list of Zenoh endpoints like tls/HOST:7447"
        )
    return tuple(value)


def _restart(data: Mapping[str, Any], where: str) -> RestartConfig:
    _check_keys(data, RestartConfig, where, "restart.")
    max_restarts = _typed(data, "max_restarts", int, 5, where, "restart.")
    if max_restarts < 0:
        raise ConfigError(f"{where}: restart.max_restarts must be >= 0, got {max_restarts}")
    return RestartConfig(
        backoff=_number(data, "backoff", 0.5, where, prefix="restart.", positive=True),
        max_backoff=_number(data, "max_backoff", 8.0, where, prefix="restart.", positive=True),
        max_restarts=max_restarts,
        window=_number(data, "window", 60.0, where, prefix="restart.", positive=True),
    )


def _services(data: Mapping[str, Any], where: str) -> dict[str, ServiceConfig]:
    unknown = sorted(set(data) - set(SERVICES))
    if unknown:
        raise ConfigError(
            f"{where}: unknown service services.{unknown[0]} (known: {', '.join(SERVICES)})"
        )
    services: dict[str, ServiceConfig] = {}
    for name in SERVICES:
        prefix = f"services.{name}."
        section = _section(data, name, where, "services.")
        _check_keys(section, ServiceConfig, where, prefix)
        enabled = _typed(section, "enabled", bool, service(name).enabled, where, prefix)
        services[name] = ServiceConfig(enabled, _args(section, where, prefix))
    return services


def _args(section: Mapping[str, Any], where: str, prefix: str) -> tuple[str, ...]:
    """A section's ``args``: extra command-line flags, as strings."""
    args = section.get("args", [])
    if not isinstance(args, list) or not all(isinstance(a, str | int | float) for a in args):
        raise ConfigError(f"{where}: {prefix}args must be a list of strings")
    return tuple(str(a) for a in args)


def _section(data: Mapping[str, Any], key: str, where: str, prefix: str = "") -> Mapping[str, Any]:
    value = data.get(key)
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise ConfigError(f"{where}: {prefix}{key} must be a mapping, got {_kind(value)}")
    return value


def _check_keys(data: Mapping[str, Any], model: type, where: str, prefix: str) -> None:
    known = [f.name for f in dataclasses.fields(model)]
    for key in data:
        if key not in known:
            names = ", ".join(prefix + k for k in known)
            raise ConfigError(f"{where}: unknown key {prefix}{key} (known: {names})")


def _typed(
    data: Mapping[str, Any], key: str, kind: type, default: Any, where: str, prefix: str = ""
) -> Any:
    value = data.get(key, default)
    if value is None and default is None:
        return None
    # bool is an int in Python: a "true" speed or a numeric flag is still a wrong type
    if not isinstance(value, kind) or (kind is not bool and isinstance(value, bool)):
        raise ConfigError(
            f"{where}: {prefix}{key} must be {kind.__name__}, got {_kind(value)} {value!r}"
        )
    return value


def _number(
    data: Mapping[str, Any],
    key: str,
    default: float,
    where: str,
    *,
    prefix: str = "",
    positive: bool = False,
) -> float:
    value = data.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ConfigError(f"{where}: {prefix}{key} must be a number, got {_kind(value)} {value!r}")
    if not math.isfinite(value) or (positive and value <= 0):
        raise ConfigError(f"{where}: {prefix}{key} must be a finite number > 0, got {value!r}")
    return float(value)


def _check_namespace(namespace: str, where: str) -> None:
    try:
        check_name(namespace, "namespace")
    except ValueError as exc:
        raise ConfigError(f"{where}: {exc}") from None


def _kind(value: object) -> str:
    return "null" if value is None else type(value).__name__
