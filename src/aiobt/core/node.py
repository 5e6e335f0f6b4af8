"""The node base: status bookkeeping, ports, tick and halt.

Ticks and halts are synchronous, as in BehaviorTree.CPP: a parent ticks a
child with a plain call, ``status = child.tick_sync()``, and a whole tree tick
is a chain of calls with no coroutine per node. Work that waits lives in the
tasks of async leaves (:class:`aiobt.core.leaves.AsyncActionNode`), which the
tree starts, polls and cancels; the :class:`~aiobt.core.tree.Tree` awaits
their cleanup after the tick that halted them.

Node authors implement ``execute_sync()`` (control nodes, decorators) or the
hooks of a leaf base in :mod:`aiobt.core.leaves`. A node class that defines
``async def execute()`` or ``async def on_halt()`` is refused when the class
is created: a tick never waits. Status changes notify the tree's listeners
only when the status really changes.
"""

from __future__ import annotations

import asyncio
import inspect
import logging
import types
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import SYSTEM_CLOCK, Clock
from aiobt.core.convert import converter_for
from aiobt.core.errors import LogicError, NodeError, PortError
from aiobt.core.ports import NO_DEFAULT, PortInfo
from aiobt.core.status import IDLE, SKIPPED, Status

if TYPE_CHECKING:
    from aiobt.core.conditions import NodeConditions


log = logging.getLogger("aiobt.core.node")

StatusListener = Callable[[float, "TreeNode", Status, Status], None]


class NodeKind:
    """BT.CPP's node types, as written in XML (``<Action ID=...>``)."""

    ACTION = "Action"
    CONDITION = "Condition"
    CONTROL = "Control"
    DECORATOR = "Decorator"
    SUBTREE = "SubTree"


class TreeContext:
    """What every node of one tree shares: clock, wake-up, listeners, and the
    cleanups of halted async leaves, which the tree awaits after a tick."""

    __slots__ = ("cleanups", "clock", "enums", "halt_timeout", "listeners", "wake_up")

    def __init__(self, clock: Clock | None = None, halt_timeout: float = 2.0) -> None:
        self.clock: Clock = clock if clock is not None else SYSTEM_CLOCK
        self.listeners: list[StatusListener] = []
        self.wake_up: Callable[[], None] = _no_wake_up
        self.enums: dict[str, int] = {}
        self.halt_timeout = halt_timeout
        self.cleanups: dict[asyncio.Task[Any], str] = {}

    async def settle(self) -> None:
        """Wait for the cleanups of halted async leaves, each bounded by ``halt_timeout``."""
        if not self.cleanups:
            return
        pending, self.cleanups = self.cleanups, {}
        done, late = await asyncio.wait(set(pending), timeout=self.halt_timeout)
        for task in late:
            log.warning(
                "%s: run() did not finish its cleanup within %.1f s of halt",
                pending[task],
                self.halt_timeout,
            )
        for task in done:
            if not task.cancelled() and task.exception() is not None:
                log.warning("%s: run() raised while halting: %r", pending[task], task.exception())


def _no_wake_up() -> None:
    return None


@dataclass(slots=True)
class PortBinding:
    """An input port as loaded: a converted literal, or a blackboard key."""

    key: str | None
    value: Any = None
    converter: Callable[[str], Any] | None = None
    text: str = ""


@dataclass(slots=True)
class NodeConfig:
    """Everything a node needs from the tree that built it."""

    blackboard: Blackboard = field(default_factory=Blackboard.create)
    inputs: dict[str, PortBinding] = field(default_factory=dict)
    outputs: dict[str, str] = field(default_factory=dict)
    ports: dict[str, PortInfo] = field(default_factory=dict)
    path: str = ""
    uid: int = 0
    registration_id: str = ""
    attributes: dict[str, str] = field(default_factory=dict)
    context: TreeContext = field(default_factory=TreeContext)


class PortSource(Protocol):
    """Anything that declares ports (a node class, a manifest)."""

    @classmethod
    def provided_ports(cls) -> tuple[PortInfo, ...]: ...


def own_copy(function: Callable[..., Any]) -> Any:
    """``function`` with a copy of its code object.

    CPython specialises bytecode in place, per code object: a hot tick shared
    by many classes keeps missing its caches (each call site sees many types).
    A class (or a node) given its own copy gets caches that see it alone.
    """
    copy = types.FunctionType(
        function.__code__.replace(),
        function.__globals__,
        function.__name__,
        function.__defaults__,
        function.__closure__,
    )
    copy.__kwdefaults__ = function.__kwdefaults__
    copy.__qualname__ = function.__qualname__
    copy.__doc__ = function.__doc__
    copy.__dict__.update(function.__dict__)  # e.g. __wrapped__ of a decorated tick
    return copy


class TreeNode:
    """Base of every node. Subclasses implement ``execute_sync()``."""

    __slots__ = ("_conditions", "_ctx", "_status", "config", "name")

    KIND: ClassVar[str] = NodeKind.ACTION
    PORTS: ClassVar[tuple[PortInfo, ...]] = ()

    def __init__(self, name: str, config: NodeConfig | None = None) -> None:
        self.name = name
        self.config = config if config is not None else NodeConfig()
        self._ctx = self.config.context
        self._status = IDLE
        self._conditions: NodeConditions | None = None

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        for name, sync_name in (("execute", "execute_sync"), ("on_halt", "on_halt_sync")):
            if inspect.iscoroutinefunction(cls.__dict__.get(name)):
                raise TypeError(
                    f"{cls.__qualname__}.{name} is a coroutine function: a tick or a halt "
                    f"never waits; write def {sync_name}(self) instead, and put the "
                    "waiting in an AsyncActionNode's async def run()"
                )

    @classmethod
    def provided_ports(cls) -> tuple[PortInfo, ...]:
        return cls.PORTS

    # -- identity and status --------------------------------------------------
    @property
    def status(self) -> Status:
        return self._status

    @property
    def path(self) -> str:
        return self.config.path or self.name

    @property
    def uid(self) -> int:
        return self.config.uid

    @property
    def clock(self) -> Clock:
        return self._ctx.clock

    @property
    def blackboard(self) -> Blackboard:
        return self.config.blackboard

    def children_nodes(self) -> tuple[TreeNode, ...]:
        return ()

    def _set_status(self, status: Status) -> None:
        previous = self._status
        if previous is status:
            return
        self._status = status
        listeners = self._ctx.listeners
        if listeners:
            now = self._ctx.clock.now()
            for listener in listeners:
                listener(now, self, previous, status)

    def reset_status(self) -> None:
        """Back to IDLE without halting (BT.CPP's resetStatus)."""
        self._set_status(IDLE)

    def emit_wake_up(self) -> None:
        """Ask the tree to tick again now instead of after its period."""
        self._ctx.wake_up()

    def logic_error(self, message: str) -> NodeError:
        """A LogicError naming this node, to raise from ``execute``."""
        return NodeError(self.path, LogicError(message))

    def attach_conditions(self, conditions: NodeConditions | None) -> None:
        self._conditions = conditions

    def on_tree_built(self) -> None:
        """Called once by :class:`Tree` when the tree holding this node is complete
        (its children are final). A node may prepare its hot path here.

        The default gives the node's class its own copy of an inherited
        ``tick_sync`` (:func:`own_copy`), so that the tick's call of the
        class's hooks is specialised for that class alone. (A ``tick_sync``
        patched onto a base class later is not seen by subclasses copied
        before.)
        """
        cls = type(self)
        if "tick_sync" not in cls.__dict__:
            cls.tick_sync = own_copy(cls.tick_sync)  # type: ignore[method-assign]

    # -- tick and halt ------------------------------------------------------------
    def tick_sync(self) -> Status:
        """Tick once: pre-conditions, :meth:`execute_sync`, status, post-conditions."""
        conditions = self._conditions
        if conditions is not None:
            return conditions.tick_sync(self)
        try:
            status = self.execute_sync()
        except NodeError:
            raise
        except Exception as exc:  # a node's own error, named by its path
            raise NodeError(self.path, exc) from exc
        if status is not SKIPPED and status is not self._status:
            if self._ctx.listeners:
                self._set_status(status)
            else:
                self._status = status
        return status

    async def tick(self) -> Status:
        """:meth:`tick_sync`, awaitable (for code written against the async API)."""
        return self.tick_sync()

    def execute_sync(self) -> Status:
        """The node's own logic; returns its new status. Never waits."""
        raise LogicError(f"{type(self).__name__} does not implement execute_sync()")

    def halt_sync(self) -> None:
        """Stop the node and reset it to IDLE (BT.CPP's haltNode)."""
        try:
            self.on_halt_sync()
        except NodeError:
            raise
        except Exception as exc:
            raise NodeError(self.path, exc) from exc
        self._set_status(IDLE)
        if self._conditions is not None:
            self._conditions.on_halted(self)

    def on_halt_sync(self) -> None:
        """Node-specific halt work; the default has none. Never waits."""
        return

    async def halt(self) -> None:
        """:meth:`halt_sync`, then wait for the cleanup of the async leaves it halted."""
        self.halt_sync()
        await self._ctx.settle()

    # -- ports ------------------------------------------------------------------------
    def get_input(self, name: str, default: Any = NO_DEFAULT) -> Any:
        """The value of input port ``name``, converted to the port's type."""
        binding = self.config.inputs.get(name)
        if binding is None:
            if default is not NO_DEFAULT:
                return default
            if name not in self.config.ports:
                raise PortError(f"{self.path}: input port [{name}] is not declared")
            raise PortError(f"{self.path}: input port [{name}] is not set and has no default")
        if binding.key is None:
            return binding.value
        entry = self.config.blackboard.entry(binding.key)
        if entry is None or not entry.has_value:
            if default is not NO_DEFAULT:
                return default
            raise PortError(
                f"{self.path}: input port [{name}] reads blackboard key "
                f"[{binding.key}], which has no value"
            )
        value = entry.value
        if binding.converter is not None and isinstance(value, str):
            try:
                value = binding.converter(value)
            except (TypeError, ValueError) as exc:
                raise PortError(
                    f"{self.path}: input port [{name}]: cannot convert {value!r} "
                    f"from blackboard key [{binding.key}]: {exc}"
                ) from exc
        return value

    def get_input_or_blackboard(self, name: str, default: Any = NO_DEFAULT) -> Any:
        """Nav2's fallback: the port if set, else the blackboard key of its name (text
        there is converted to the port's type, as a typed port read converts it)."""
        if name in self.config.inputs:
            return self.get_input(name, default)
        entry = self.config.blackboard.entry(name)
        if entry is not None and entry.has_value:
            return self._typed(name, entry.value)
        if default is not NO_DEFAULT:
            return default
        raise PortError(f"{self.path}: neither port [{name}] nor blackboard key [{name}] is set")

    def _typed(self, name: str, value: Any) -> Any:
        port = self.config.ports.get(name)
        if not isinstance(value, str) or port is None or port.type in (None, str):
            return value
        converter = converter_for(port.type)
        if converter is None:
            return value
        try:
            return converter(value)
        except (TypeError, ValueError) as exc:
            raise PortError(
                f"{self.path}: blackboard key [{name}] (for port [{name}]): "
                f"cannot convert {value!r}: {exc}"
            ) from exc

    def has_input(self, name: str) -> bool:
        return name in self.config.inputs

    def set_output(self, name: str, value: Any) -> bool:
        """Write output port ``name``; False when the port is not connected."""
        key = self.config.outputs.get(name)
        if key is None:
            info = self.config.ports.get(name)
            if info is None or not info.is_output:
                raise PortError(f"{self.path}: output port [{name}] is not declared")
            return False
        self.config.blackboard.set(key, value)
        return True

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.path} {self._status.name}>"


def tick_error(node: TreeNode, exc: BaseException) -> NodeError:
    """Wrap an exception raised by node code, naming the node once."""
    if isinstance(exc, NodeError):
        return exc
    return NodeError(node.path, exc)
