"""Tell the person following a navigation when a service it depends on goes or comes back.

A service's liveliness token ``{ns}/nodes/<name>`` goes when its process dies (or
is restarted by ``aiobt up``) and comes back with the new process: each is one
line, e.g. ``planner went away (aiobt up restarts a crashed service)`` and
``planner is back``. A service already up when watching begins says nothing.
"""

from __future__ import annotations

from collections.abc import Callable

from aiobt.transport import Bus

SERVICES = ("robot", "planner", "controller", "behaviors", "navigator")


def watch_services(
    bus: Bus, say: Callable[[str], None], services: tuple[str, ...] = SERVICES
) -> ServiceNews:
    """Calls ``say`` with a line when one of ``services`` goes away or comes back."""
    news = ServiceNews(say)
    for name in services:
        bus.presence(bus.keys.topic(f"nodes/{name}")).add_listener(news.listener(name))
    return news


class ServiceNews:
    """The lines for services' comings and goings (see :func:`watch_services`)."""

    def __init__(self, say: Callable[[str], None]) -> None:
        self.say = say
        self.gone: set[str] = set()

    def listener(self, name: str) -> Callable[[bool], None]:
        def changed(present: bool) -> None:
            self.changed(name, present)

        return changed

    def changed(self, name: str, present: bool) -> None:
        if not present:
            self.gone.add(name)
            self.say(f"{name} went away (aiobt up restarts a crashed service)")
        elif name in self.gone:
            self.gone.discard(name)
            self.say(f"{name} is back")
