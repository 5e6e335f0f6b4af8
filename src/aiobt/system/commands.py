"""The command line of every service, as ``aiobt up`` and docker-compose.yml run them.

A command is the ``aiobt`` sub-command and its flags (``["robot", "--connect",
..., "--world", "office"]``); :func:`process_argv` turns it into what a local
process runs. docker-compose.yml writes the same commands with the router's
container name as the endpoint (tests/integration/system checks they agree).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from aiobt.system.catalog import COMPOSITIONS, SAFETY_CHAIN, service
from aiobt.system.config import SystemConfig
from aiobt.system.world_start import Start, WorldError, start_from_args, world_start

# the localization's shipped params for the simulated robot (its README says why)
LOCALIZATION_PARAMS = ("--params-file", "sim_robot")


def available(name: str) -> bool:
    """Whether ``name`` is a service (or a composition of them) and its module is installed."""
    if name in COMPOSITIONS:
        return all(available(part) for part in COMPOSITIONS[name])
    try:
        return importlib.util.find_spec(service(name).module) is not None
    except (KeyError, ModuleNotFoundError):
        return False


def processes(config: SystemConfig) -> list[str]:
    """The processes ``aiobt up`` runs: the enabled services, with the safety chain's
    two as one ``safety_chain`` where ``use_composition`` (and both are enabled; not
    with ``router.certs``: one session presents one certificate, and each has its own)."""
    names = config.enabled()
    composed = config.use_composition and not config.router.certs
    if not (composed and set(SAFETY_CHAIN) <= set(names)):
        return names
    at = names.index(SAFETY_CHAIN[0])
    rest = [name for name in names if name not in SAFETY_CHAIN]
    return [*rest[:at], "safety_chain", *rest[at:]]


def router_command(config: SystemConfig) -> list[str]:
    """The router's: where it listens, the routers it joins, its certificate and rules."""
    router = config.router
    command = ["router", "--listen", router.listen]
    for endpoint in router.connect:
        command += ["--connect", endpoint]
    if router.certs:
        command += ["--config", identity_config(config, f"router-{router.host}")]
    if router.access_control:
        command += ["--access-control", router.access_control]
    return command + list(router.args)


def identity_config(config: SystemConfig, name: str) -> str:
    """The Zenoh config file that makes a session present ``name``'s certificate."""
    assert config.router.certs is not None
    return str(Path(config.router.certs) / f"{name}.json5")


def service_command(name: str, config: SystemConfig) -> list[str]:
    """``name``'s sub-command and flags: the common bus flags, then its own, then the extras."""
    if name in COMPOSITIONS:
        return composed_command(name, config)
    command = [name, "--connect", config.router.listen, "--namespace", config.namespace]
    if config.router.certs:
        command += ["--config", identity_config(config, name)]
    spec = service(name)
    simulation = spec.simulation
    if simulation:
        command += ["--world", config.world, "--speed", f"{config.speed:g}"]
    if spec.world_flag:  # e.g. the route server: the world's name picks its graph
        command += [spec.world_flag, config.world]
    if config.uses_sim_time and not simulation:
        command.append("--sim-time")
    if config.safety_chain and name in ("controller", "behaviors"):
        command += ["--cmd-vel-topic", "cmd_vel_nav"]  # through smoother and monitor
    if name == "localization" and config.services["robot"].enabled:
        command += [*LOCALIZATION_PARAMS, *initial_pose_flags(simulated_start(config))]
    return command + list(config.services[name].args)


def composed_command(name: str, config: SystemConfig) -> list[str]:
    """Composition ``name``'s: the bus and clock flags once, then each service's extras
    (``services.<service>.args``, the flags as each takes them alone; see
    :mod:`aiobt.system.compose`)."""
    command = [name, "--connect", config.router.listen, "--namespace", config.namespace]
    if config.uses_sim_time:
        command.append("--sim-time")
    return command + [arg for part in COMPOSITIONS[name] for arg in config.services[part].args]


def simulated_start(config: SystemConfig) -> Start | None:
    """Where the simulation ``config`` runs puts the robot: the robot's ``--start``, else
    the world's; None when the world's file or the flag cannot be read (the robot then
    stops at start naming it, and localization waits for an initialpose)."""
    try:
        return start_from_args(config.services["robot"].args) or world_start(config.world)
    except WorldError:
        return None


def initial_pose_flags(start: Start | None) -> list[str]:
    """AMCL's ``set_initial_pose`` at ``start``: the localization's flags (none without)."""
    if start is None:
        return []
    x, y, yaw = start
    return ["--set", "set_initial_pose=true",
            "--set", f"initial_pose={{x: {x:g}, y: {y:g}, yaw: {yaw:g}}}"]  # fmt: skip


def process_argv(command: list[str]) -> list[str]:
    """The local process for an ``aiobt`` sub-command: this Python, not a PATH lookup."""
    return [sys.executable, "-m", "aiobt.cli.main", *command]
