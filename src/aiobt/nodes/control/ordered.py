"""The two shapes behind Sequence/Fallback and their reactive variants.

A Sequence is a Fallback with SUCCESS and FAILURE swapped: children are
ticked in order while they return the status that lets the walk go on
(``NEXT``); the other one (``STOP``) ends it. One implementation serves both.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar

from aiobt.core.composite import ControlNode, reset_all, reset_node
from aiobt.core.errors import LogicError
from aiobt.core.node import TreeNode
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.nodes.control.unrolled import reroll, reset_from, unroll


def _short_path(proceed: Status, stop: Status) -> Any:
    """The common tick of the four composites, kept as short as it can be.

    It applies when the walk starts from the first child (not resuming a
    RUNNING one), nobody listens to status changes and no pre/post conditions
    are attached. It handles the walks that end on a child returning RUNNING
    (the class's ``_on_running``) or ``stop`` after children that all returned
    ``proceed``, or with every child returning ``proceed``; anything else goes
    to the class's general ``_walk`` or its ``_tail``. The frame is small on
    purpose (few locals and cells; helpers are methods): deep trees recurse
    through it once per level, and CPython 3.11 allocates a new stack chunk
    per tick when they outgrow one (``tests/unit/nodes/test_frame_size.py``).
    Trees that are built use :mod:`unrolled` ticks for composites of up to 12
    children; this one serves larger ones.
    """

    def fast(self: Any) -> Status:
        if self._current or self._conditions is not None or self._ctx.listeners:
            return self._walk()  # type: ignore[no-any-return]
        status: Status
        for child in self.children:
            status = child.tick_sync()
            if status is not proceed:
                break
        else:
            status = proceed
        if status is not proceed and status is not stop:
            # (out of the loop: the iterator's stack slot is free again)
            if status is RUNNING:
                self._on_running(child)
                self._status = RUNNING
                return RUNNING
            return self._tail(child, status)  # type: ignore[no-any-return]
        reset_from(self.children, 0)
        self._status = status
        return status

    return fast


def _ordered_walk(proceed: Status, stop: Status, yields: bool, write: bool) -> Any:
    """The tick of an ordered composite, specialised per (NEXT, STOP, YIELDS).

    With ``write`` it is the whole ``tick_sync`` (conditions check and final
    status write included); without, the ``execute_sync`` that pre/post
    conditions wrap. The constants are closure cells: the hot path of every
    tree reads no class attribute, and statuses are written in place when
    nobody listens.
    """

    def walk(self: OrderedComposite) -> Status:
        if write and self._conditions is not None:
            return self._conditions.tick_sync(self)
        quiet = not self._ctx.listeners
        if self._status is not RUNNING:
            if self._status is IDLE and self._skipped:
                self._skipped = 0
            # RUNNING is only observable through listeners until the walk
            # returns; when nobody listens it is written on the paths that keep it
            if not quiet:
                self._set_status(RUNNING)
        children = self.children
        start = current = self._current
        for child in children[start:] if start else children:
            previous = child._status if yields else IDLE
            status = child.tick_sync()
            if status is proceed:
                current += 1
                if yields and previous is IDLE and current < len(children):
                    self._current = current
                    self._status = RUNNING
                    self.emit_wake_up()
                    return RUNNING
            elif status is RUNNING:
                if current != start:
                    self._current = current
                self._status = RUNNING
                return RUNNING
            elif status is stop:
                if start:
                    self._current = 0
                break
            elif status is SKIPPED:
                current += 1
                self._skipped += 1
            else:
                self._status = RUNNING
                raise self.logic_error(f"child {child.path} returned IDLE")
        else:
            if start:
                self._current = 0
            status = proceed
            if self._skipped:
                if self._skipped == len(children):
                    status = SKIPPED
                self._skipped = 0
        _reset(children, quiet)
        if status is SKIPPED:
            self._status = RUNNING  # BT.CPP: a SKIPPED result leaves the node RUNNING
            return status
        if write:
            if quiet:
                self._status = status
            else:
                self._set_status(status)
        elif quiet:
            self._status = RUNNING  # the caller (pre/post conditions) writes the result
        return status

    if yields or not write:
        return walk

    fast = _short_path(proceed, stop)

    def tail(self: OrderedComposite, child: TreeNode, status: Status) -> Status:
        """The fast walk met a child that did not return NEXT (all before it did)."""
        children = self.children
        index = children.index(child)
        if status is RUNNING:
            self._current = index
            self._status = RUNNING
            return RUNNING
        if status is stop:
            reset_from(children, 0)
            self._status = stop
            return stop
        self._status = RUNNING  # what BT.CPP's node shows during its tick
        if status is SKIPPED:  # go on after it, counting the skip, as ``walk`` does
            self._current = index + 1
            self._skipped = 1
            return walk(self)
        raise self.logic_error(f"child {child.path} returned IDLE")

    fast.tail = tail
    fast.walk = walk
    return fast


class WalkedComposite(ControlNode):
    """What both composites share: ``NEXT``/``STOP`` (the child results that
    continue or end the walk), the resume index, and a tick built per class
    from ``_make_tick`` when the class is created (the short path in
    ``tick_sync``, the general ``_walk`` and ``_tail`` behind it)."""

    __slots__ = ("_current",)
    NEXT: ClassVar[Status] = SUCCESS
    STOP: ClassVar[Status] = FAILURE
    _walk: ClassVar[Callable[[Any], Status]]
    _tail: ClassVar[Callable[[Any, TreeNode, Status], Status]]

    @classmethod
    def _make_tick(cls, write: bool) -> Any:
        raise LogicError(f"{cls.__name__} does not say how it walks its children")

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "tick_sync" not in cls.__dict__:  # a subclass may wrap the tick (statistics)
            tick = cls._make_tick(True)
            cls.tick_sync = tick  # type: ignore[method-assign]
            cls._walk = getattr(tick, "walk", tick)
            cls._tail = getattr(tick, "tail", tick)  # (unused by the yielding variants)
        if "execute_sync" not in cls.__dict__:
            cls.execute_sync = cls._make_tick(False)  # type: ignore[method-assign]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0  # always 0 for the reactive pair

    def on_tree_built(self) -> None:
        """Switch to a tick unrolled for these children (:mod:`unrolled`)."""
        unroll(self, reactive=isinstance(self, ReactiveComposite))

    def add_child(self, child: TreeNode) -> None:
        reroll(self)  # a child added to a built tree: back to the shared tick
        super().add_child(child)


class OrderedComposite(WalkedComposite):
    """Tick children in order, resuming at the RUNNING one (memory of the index).

    - a child RUNNING: RUNNING, and the same child is ticked next time;
    - a child ``STOP``: reset all children, start over next time, ``STOP``;
    - every child ``NEXT`` (or SKIPPED): reset, ``NEXT`` (SKIPPED if all were
      skipped);
    - ``YIELDS``: after a child that started from IDLE returns ``NEXT``,
      return RUNNING and ask for a wake-up (the Async variants).

    Subclasses set ``NEXT``, ``STOP`` and ``YIELDS``; the tick is built for
    them when the class is created.
    """

    __slots__ = ("_skipped",)
    YIELDS: ClassVar[bool] = False

    @classmethod
    def _make_tick(cls, write: bool) -> Any:
        return _ordered_walk(cls.NEXT, cls.STOP, cls.YIELDS, write)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._skipped = 0

    def on_halt_sync(self) -> None:
        self._current = self._skipped = 0
        reset_all(self.children)

    def _on_running(self, child: TreeNode) -> None:
        """(The short path) ``child`` is RUNNING: resume there next tick."""
        self._current = self.children.index(child)


def _reactive_walk(proceed: Status, stop: Status, write: bool) -> Any:
    """The tick of a reactive composite, specialised like :func:`_ordered_walk`."""

    def walk(self: ReactiveComposite) -> Status:
        if write and self._conditions is not None:
            return self._conditions.tick_sync(self)
        quiet = not self._ctx.listeners
        if self._status is not RUNNING:
            if quiet:
                self._status = RUNNING
            else:
                self._set_status(RUNNING)
        all_skipped = True
        children = self.children
        for index, child in enumerate(children):
            status = child.tick_sync()
            if status is proceed:
                all_skipped = False
            elif status is RUNNING:
                # the children before it just finished; a later one may still run
                _reset(children[:index], quiet)
                reset_all(children[index + 1 :])
                return RUNNING
            elif status is stop:
                reset_all(children)
                break
            elif status is SKIPPED:
                reset_node(child)  # BT.CPP: reset at once, "to allow it to be skipped again"
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        else:
            _reset(children, quiet)
            if all_skipped:
                return SKIPPED
            status = proceed
        if write:
            if quiet:
                self._status = status
            else:
                self._set_status(status)
        return status

    if not write:
        return walk

    fast = _short_path(proceed, stop)

    def tail(self: ReactiveComposite, child: TreeNode, status: Status) -> Status:
        """The fast walk met a child that did not return NEXT: finish the walk."""
        children = self.children
        index = children.index(child)
        all_skipped = index == 0  # the children before it returned NEXT
        while True:
            if status is proceed:
                all_skipped = False
            elif status is RUNNING:
                _reset_around(children, index)
                self._status = RUNNING
                return RUNNING
            elif status is stop:
                reset_all(children)
                self._status = stop
                return stop
            elif status is SKIPPED:
                reset_node(children[index])  # at once, as BT.CPP does
            else:
                self._status = RUNNING
                raise self.logic_error(f"child {children[index].path} returned IDLE")
            index += 1
            if index == len(children):
                break
            status = children[index].tick_sync()
        reset_from(children, 0)
        if all_skipped:
            self._status = RUNNING  # BT.CPP: a SKIPPED result leaves the node RUNNING
            return SKIPPED
        self._status = proceed
        return proceed

    fast.tail = tail
    fast.walk = walk
    return fast


class ReactiveComposite(WalkedComposite):
    """Tick every child from the first on every tick (no memory of the index).

    - a child RUNNING: every other child is reset (a RUNNING one halted),
      RUNNING; so the children before a running one are re-checked each tick;
    - a child ``STOP``: reset all, ``STOP``;
    - all ``NEXT`` (or SKIPPED): reset all, ``NEXT`` (SKIPPED if all skipped).
    """

    __slots__ = ()

    @classmethod
    def _make_tick(cls, write: bool) -> Any:
        return _reactive_walk(cls.NEXT, cls.STOP, write)

    def _on_running(self, child: TreeNode) -> None:
        """(The short path) ``child`` is RUNNING: reset every other child."""
        _reset_around(self.children, self.children.index(child))


def _reset_around(children: list[TreeNode], index: int) -> None:
    """The child at ``index`` is RUNNING and nobody listens: reset every other
    child, in order (BT.CPP's haltChild). Those before it returned NEXT or were
    reset when skipped, so none runs; a later one may."""
    for child in children[:index]:
        child._status = IDLE
    reset_from(children, index + 1)


def _reset(children: list[TreeNode], quiet: bool) -> None:
    """Reset ``children`` that were just ticked: IDLE, in place when nobody listens.

    A child is RUNNING here only if it was skipped after setting itself
    RUNNING (a control node keeps that status, as in BT.CPP): it is halted.
    """
    if quiet:
        reset_from(children, 0)
        return
    for child in children:
        status = child._status
        if status is RUNNING:
            child.halt_sync()
        elif status is not IDLE:
            child._set_status(IDLE)
