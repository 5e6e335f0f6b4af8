"""One subscription per key per process, shared by every Nav2 node on a bus.

Nav2's nodes each open their own ROS subscription; here every node and every
tree that reads ``{ns}/odom`` (or a selector's topic) on the same bus and
namespace shares one Zenoh subscription, declared on first use and kept until
the bus closes. The last good message is kept: a malformed payload is dropped
and reported once by the subscription, so a node reading ``latest`` never
sees it and never raises because of it.
"""

from __future__ import annotations

import logging
import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from aiobt.core.errors import LogicError
from aiobt.msgs import Msg
from aiobt.transport.keys import check_name

if TYPE_CHECKING:
    from aiobt.nav.context import NavContext
    from aiobt.transport import Bus, Subscription

M = TypeVar("M", bound=Msg)
log = logging.getLogger("aiobt.nav.shared_topics")


class SharedTopic(Generic[M]):
    """The last good message on one key (``latest``, None until one came) and the
    functions called with every message (``listen``)."""

    __slots__ = ("_listeners", "key", "latched", "latest", "model", "received", "subscription")

    def __init__(self, key: str, model: type[M], latched: bool) -> None:
        self.key = key
        self.model = model
        self.latched = latched
        self.latest: M | None = None
        self.received = 0
        self.subscription: Subscription[M] | None = None
        self._listeners: list[Callable[[M], object]] = []

    def listen(self, listener: Callable[[M], object]) -> None:
        """Call ``listener(message)`` in the event loop for every good message."""
        self._listeners.append(listener)

    def deliver(self, message: M) -> None:
        self.latest = message
        self.received += 1
        for listener in self._listeners:
            try:
                listener(message)
            except Exception:
                log.exception("%s: listener %r failed", self.key, listener)


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

    def topic(self, name: str, model: type[M], *, latched: bool = False) -> SharedTopic[M]:
        """The shared reader of ``{ns}/{name}``, subscribed on the first call."""
        found = self._topics.get(name)
        if found is not None:
            if found.model is not model:
                raise LogicError(
                    f"{found.key} is read as {found.model.__name__} and as {model.__name__}: "
                    "one key carries one message type"
                )
            return found
        topic: SharedTopic[M] = SharedTopic(f"{self.namespace}/{name}", model, latched)
        self._declare(name, topic)
        self._topics[name] = topic
        return topic

    def _declare(self, name: str, topic: SharedTopic[M]) -> Subscription[M]:
        topic.subscription = self.bus.subscribe(
            name, topic.model, topic.deliver, latched=topic.latched, namespace=self.namespace
        )
        log.debug("subscribed to %s (%s)", topic.key, topic.model.__name__)
        return topic.subscription

    def pause(self) -> None:
        """Close the subscriptions of the topics not latched (the robot's streams) and
        forget their last message, until :meth:`resume`; listeners stay registered."""
        for topic in self._topics.values():
            if topic.latched or topic.subscription is None:
                continue
            topic.subscription.close()
            topic.subscription = None
            topic.latest = None

    def resume(self) -> dict[str, Subscription[Any]]:
        """Subscribe again to the paused topics; every topic's subscription, by name."""
        subs: dict[str, Subscription[Any]] = {}
        for name, topic in self._topics.items():
            sub = topic.subscription
            subs[name] = sub if sub is not None else self._declare(name, topic)
        return subs

    def subscribed(self) -> list[str]:
        """The keys subscribed so far."""
        return [topic.key for topic in self._topics.values()]

    def live(self) -> list[str]:
        """The keys subscribed now (not paused)."""
        return [topic.key for topic in self._topics.values() if topic.subscription is not None]

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
