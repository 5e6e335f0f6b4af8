"""One subscription per key per process, shared by every Nav2 node on a bus.

Nav2's nodes each open their own ROS subscription; here every node and every
tree that reads ``{ns}/odom`` (or a selector's topic) on the same bus and
namespace shares one Zenoh subscription, declared on first use and kept until
the bus closes. It is read, not delivered: Zenoh keeps the newest payload in a
ring and a node reading ``latest`` decodes it (``Bus.latest``). The last good
message is kept: a malformed payload is dropped and reported once, so a node
reading ``latest`` never sees it and never raises because of it.
"""

from __future__ import annotations

import logging
import weakref
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from aiobt.core.errors import LogicError
from aiobt.msgs import Msg
from aiobt.transport.keys import check_name

if TYPE_CHECKING:
    from aiobt.nav.context import NavContext
    from aiobt.transport import Bus, Latest

M = TypeVar("M", bound=Msg)
log = logging.getLogger("aiobt.nav.shared_topics")


class SharedTopic(Generic[M]):
    """The newest good message on one key (``latest``, None until one came), read
    through :meth:`Bus.latest <aiobt.transport.Bus.latest>`: Zenoh keeps the payload
    in a ring, a reader decodes it. No message wakes the event loop: at a sim speed-up
    of 10 the robot's pose and odometry are 1,000 messages a wall second, each a
    hand-over to the navigator's loop and a decode when they were delivered.
    ``keep`` > 1 also keeps the last ``keep`` messages (:meth:`newest_first`)."""

    __slots__ = ("_received", "keep", "key", "latched", "model", "reader")

    def __init__(self, key: str, model: type[M], latched: bool, keep: int = 1) -> None:
        self.key = key
        self.model = model
        self.latched = latched
        self.keep = keep
        self.reader: Latest[M] | None = None
        self._received = 0  # by readers closed before (a pause)

    @property
    def latest(self) -> M | None:
        reader = self.reader
        return None if reader is None else reader.get()

    def get(self) -> M | None:
        """:attr:`latest` (what a :class:`~aiobt.transport.Latest` reader answers)."""
        return self.latest

    @property
    def received(self) -> int:
        """Messages taken (good or not) since the topic was first subscribed (reading
        takes what came; one pushed out by newer ones before a read is not counted)."""
        reader = self.reader
        return self._received + (0 if reader is None else reader.received)

    def newest_first(self) -> Iterator[M]:
        """The kept messages, newest first, decoded as far as the iteration goes."""
        reader = self.reader
        return iter(()) if reader is None else reader.newest_first()

    async def wait_latest(self, timeout: float | None = None) -> M:  # noqa: ASYNC109
        """The newest good message, waiting (at most ``timeout`` s) for one."""
        if self.reader is None:
            raise LogicError(f"{self.key} is paused: nothing to wait for")
        return await self.reader.wait_latest(timeout)

    def close(self) -> None:
        """Stop reading (a pause): ``latest`` is None until read again."""
        reader, self.reader = self.reader, None
        if reader is not None:
            self._received += reader.received
            reader.close()


class SharedTopics:
    """The shared subscriptions (and shared helpers) of one bus and namespace."""

    def __init__(self, bus: Bus, namespace: str) -> None:
        self._bus = weakref.ref(bus)  # weak: the registry below is keyed by the bus
        self.namespace = namespace
        self._topics: dict[str, SharedTopic[Any]] = {}
        self._shared: dict[str, Any] = {}

    @property
    def bus(self) -> Bus:
        bus = self._bus()
        if bus is None:
            raise LogicError(f"the bus of namespace {self.namespace!r} is gone")
        return bus

    def topic(
        self, name: str, model: type[M], *, latched: bool = False, keep: int = 1
    ) -> SharedTopic[M]:
        """The shared reader of ``{ns}/{name}``, subscribed on the first call (which
        sets ``keep``: the messages kept for :meth:`SharedTopic.newest_first`)."""
        found = self._topics.get(name)
        if found is not None:
            if found.model is not model:
                raise LogicError(
                    f"{found.key} is read as {found.model.__name__} and as {model.__name__}: "
                    "one key carries one message type"
                )
            if keep > found.keep:
                raise LogicError(
                    f"{found.key} keeps {found.keep} messages, asked for {keep}: "
                    "the first reader sets how many"
                )
            return found
        topic: SharedTopic[M] = SharedTopic(f"{self.namespace}/{name}", model, latched, keep)
        self._declare(name, topic)
        self._topics[name] = topic
        return topic

    def _declare(self, name: str, topic: SharedTopic[M]) -> Latest[M]:
        topic.reader = self.bus.latest(
            name, topic.model, latched=topic.latched, namespace=self.namespace, keep=topic.keep
        )
        log.debug("subscribed to %s (%s)", topic.key, topic.model.__name__)
        return topic.reader

    def pause(self) -> None:
        """Stop reading the topics not latched (the robot's streams) and forget their
        last message, until :meth:`resume`."""
        for topic in self._topics.values():
            if not topic.latched:
                topic.close()

    def resume(self) -> dict[str, Latest[Any]]:
        """Read the paused topics again; every topic's reader, by name."""
        readers: dict[str, Latest[Any]] = {}
        for name, topic in self._topics.items():
            reader = topic.reader
            readers[name] = reader if reader is not None else self._declare(name, topic)
        return readers

    def subscribed(self) -> list[str]:
        """The keys subscribed so far."""
        return [topic.key for topic in self._topics.values()]

    def live(self) -> list[str]:
        """The keys subscribed now (not paused)."""
        return [topic.key for topic in self._topics.values() if topic.reader is not None]

    def shared(self, name: str, make: Callable[[SharedTopics], Any]) -> Any:
        """One ``make(self)`` per bus and namespace (e.g. the odometry smoother)."""
        value = self._shared.get(name)
        if value is None:
            value = self._shared[name] = make(self)
        return value


_BY_BUS: weakref.WeakKeyDictionary[Bus, dict[str, SharedTopics]] = weakref.WeakKeyDictionary()


def shared_topics(nav: NavContext, who: str) -> SharedTopics:
    """The :class:`SharedTopics` of ``nav``'s bus and namespace; a LogicError naming
    ``who`` when the factory has no bus."""
    bus = nav.require_bus(who)
    namespace = nav.namespace or bus.namespace
    per_bus = _BY_BUS.setdefault(bus, {})
    hub = per_bus.get(namespace)
    if hub is None:
        hub = per_bus[namespace] = SharedTopics(bus, namespace)
    return hub


def topic_name(text: str, who: str, port: str) -> str:
    """A topic port's value as a key under the namespace: ROS's leading ``/`` dropped
    (``/battery_status`` is ``{ns}/battery_status``); a LogicError names a bad one."""
    name = text.strip().lstrip("/")
    try:
        return check_name(name, "topic")
    except ValueError as exc:
        raise LogicError(f"{who}: port [{port}]: {exc}") from None
