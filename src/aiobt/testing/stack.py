"""The whole navigation stack as processes: robot, localization, planner, controller,
behaviors, navigator.

Used by the end-to-end tests and the navigation benchmark. Every service is a
``python -m aiobt.cli.main <service>`` child process connected to one router
on loopback, in one fresh namespace, on the simulation's time (``--sim-time``)
at a speed-up. Readiness is each service's liveliness token
``{ns}/nodes/<service>`` (and the navigator's action servers), never a fixed
sleep; processes are stopped and killed by PID.

    with running_stack(StackConfig(speed=4.0)) as stack:   # router and processes started
        async with open_bus(stack.settings()) as bus:
            await stack.wait_ready(bus, timeout=60.0)
            stack.kill("planner")        # SIGKILL, a crash
            stack.start("planner")       # the same command again
"""

from __future__ import annotations

import contextlib
import uuid
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

from aiobt.system.catalog import COMPOSITIONS, SAFETY_CHAIN
from aiobt.system.catalog import SERVICES as CATALOG
from aiobt.system.commands import LOCALIZATION_PARAMS, initial_pose_flags
from aiobt.system.world_start import start_from_args, world_start
from aiobt.testing.bus import ServiceProcess, spawn_service, start_router
from aiobt.transport import Bus, BusSettings

# what `aiobt up` runs by default (the safety chain with StackConfig.safety_chain)
SERVICES = tuple(spec.name for spec in CATALOG if spec.enabled and spec.name not in SAFETY_CHAIN)
# the planner needs no clock
SIM_TIME = ("controller", "behaviors", "navigator", *SAFETY_CHAIN, *COMPOSITIONS)


class StackError(RuntimeError):
    """A service of the stack did not come up; the message carries its output."""


@dataclass(slots=True)
class StackConfig:
    """What the stack runs: world, speed-up, seed, Zenoh lease and extra flags per service."""

    world: str = "office"
    speed: float = 4.0
    seed: int = 7
    # a starved process (2 loaded cores) must not be taken for a hung one; a killed one is
    # still noticed at once (its connection closes)
    lease_ms: int = 5000
    # wall s without sim-clock progress before a sim-time service gives up on a goal (the
    # services' 2 s default: a robot process descheduled that long is not a dead sim here)
    clock_timeout: float = 10.0
    services: Sequence[str] = SERVICES
    extra: dict[str, list[str]] = field(default_factory=dict)
    # the velocity smoother and collision monitor between controller/behaviors and the base
    safety_chain: bool = False
    # the two in one process, ``aiobt safety_chain`` (Nav2's use_composition): each one's
    # extra flags go to it, its token is still nodes/<service> (see tokens())
    use_composition: bool = False
    # the services on the simulation's clock: None as ``aiobt up`` (on when speed != 1;
    # at 1x, as on hardware, they keep the wall clock)
    sim_time: bool | None = True

    @property
    def uses_sim_time(self) -> bool:
        return self.speed != 1.0 if self.sim_time is None else self.sim_time

    def __post_init__(self) -> None:
        chain = ("safety_chain",) if self.use_composition else SAFETY_CHAIN
        if self.safety_chain and not {*SAFETY_CHAIN, "safety_chain"} & set(self.services):
            names = list(self.services)
            at = names.index("navigator") if "navigator" in names else len(names)
            self.services = (*names[:at], *chain, *names[at:])

    def tokens(self, process: str) -> tuple[str, ...]:
        """The services whose tokens ``nodes/<service>`` say ``process`` is up."""
        return COMPOSITIONS.get(process, (process,))

    def command(self, service: str, endpoint: str, namespace: str) -> list[str]:
        """The argv (after ``python``) that starts ``service``."""
        args = ["-m", "aiobt.cli.main", service, "--connect", endpoint]
        args += ["--namespace", namespace, "--lease-ms", str(self.lease_ms)]
        if service == "robot":
            args += ["--world", self.world, "--speed", str(self.speed), "--seed", str(self.seed)]
        if service == "localization":  # seeded as the robot, told the world's start
            start = start_from_args(self.extra.get("robot", [])) or world_start(self.world)
            args += [*LOCALIZATION_PARAMS, *initial_pose_flags(start)]
            args += ["--set", f"random_seed={self.seed}"]
        if service in SIM_TIME and self.uses_sim_time:
            args += ["--sim-time", "--clock-timeout", str(self.clock_timeout)]
        if self.safety_chain and service in ("controller", "behaviors"):
            args += ["--cmd-vel-topic", "cmd_vel_nav"]
        parts = (*self.tokens(service), service) if service in COMPOSITIONS else (service,)
        return args + [flag for part in parts for flag in self.extra.get(part, [])]


class NavStack:
    """The running service processes of one namespace on one router."""

    def __init__(self, endpoint: str, config: StackConfig, namespace: str | None = None) -> None:
        self.endpoint = endpoint
        self.config = config
        self.namespace = namespace or f"e2e{uuid.uuid4().hex[:8]}"
        self.processes: dict[str, ServiceProcess] = {}
        self._retired: list[ServiceProcess] = []  # killed ones: logs kept until close

    @classmethod
    @contextlib.contextmanager
    def launch(cls, endpoint: str, config: StackConfig | None = None) -> Iterator[NavStack]:
        """Start every service of ``config``; stop them all (by PID) on exit."""
        stack = cls(endpoint, config or StackConfig())
        try:
            for service in stack.config.services:
                stack.start(service)
            yield stack
        finally:
            stack.close()

    def settings(self, **overrides: object) -> BusSettings:
        """Client settings for this stack's router and namespace."""
        values: dict[str, object] = {
            "mode": "client",
            "connect": (self.endpoint,),
            "namespace": self.namespace,
            "connect_timeout": 10.0,
            "lease_ms": self.config.lease_ms,
        }
        values.update(overrides)
        return BusSettings(**values)  # type: ignore[arg-type]

    def start(self, service: str) -> ServiceProcess:
        """Start ``service`` (again, after :meth:`kill`)."""
        if service in self.processes and self.processes[service].running:
            raise StackError(f"{service} is already running (pid {self.processes[service].pid})")
        if service in self.processes:
            self._retired.append(self.processes[service])
        proc = spawn_service(self.config.command(service, self.endpoint, self.namespace))
        self.processes[service] = proc
        return proc

    def kill(self, service: str) -> None:
        """SIGKILL ``service`` by PID (a crash) and reap it."""
        self.processes[service].kill()

    async def wait_ready(
        self,
        bus: Bus,
        services: Sequence[str] | None = None,
        timeout: float = 60.0,  # noqa: ASYNC109
    ) -> None:
        """Wait until each service's token ``{ns}/nodes/<service>`` is alive."""
        for service in services or self.config.services:
            for part in self.config.tokens(service):
                await self._wait_token(bus, service, part, timeout)

    async def _wait_token(self, bus: Bus, process: str, part: str, wait: float) -> None:
        token = bus.presence(bus.keys.topic(f"nodes/{part}"))
        if not await token.wait(wait):
            proc = self.processes.get(process)
            state = "running" if proc and proc.running else "exited"
            output = proc.output()[-4000:] if proc else "(never started)"
            raise StackError(
                f"{process} ({state}) has no token {token.key} after {wait} s:\n{output}"
            )

    def logs(self, tail: int = 6000) -> str:
        """The last ``tail`` characters of every process's output, each under its command."""
        parts = []
        for proc in [*self._retired, *self.processes.values()]:
            parts.append(f"--- {' '.join(proc.args[2:4])} (pid {proc.pid}) ---")
            parts.append(proc.output()[-tail:])
        return "\n".join(parts)

    def close(self) -> None:
        """Stop every process (SIGTERM, then SIGKILL), remove their logs."""
        with contextlib.ExitStack() as cleanups:  # every process is stopped, even if one fails to
            for proc in [*self._retired, *self.processes.values()]:
                cleanups.callback(proc.cleanup)


@contextlib.contextmanager
def running_stack(config: StackConfig | None = None) -> Iterator[NavStack]:
    """A router (with the stack's lease: a starved router is not taken for a hung one
    either; given a minute to start on a loaded machine) and the stack on it; everything
    stopped by PID on exit."""
    config = config or StackConfig()
    router, endpoint = start_router(extra_args=("--lease-ms", str(config.lease_ms)), timeout=60.0)
    try:
        with NavStack.launch(endpoint, config) as stack:
            yield stack
    finally:
        router.cleanup()
