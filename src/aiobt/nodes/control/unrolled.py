"""Per-instance short paths for Sequence, Fallback and their reactive variants.

A composite with a few children gets, when its tree is built, a tick written
for exactly its children: the loop over them unrolled, the resets unrolled,
every child a global of the function's own namespace (no closure cells, so
the frame stays small for deep trees, and every call site sees one child
type, which CPython's specialising interpreter rewards). The node's class is
swapped for a subclass of its own class (same name) holding that tick, so
every caller still dispatches through ``child.tick_sync()`` and class-level
wrappers (statistics, benchmark counters) keep working.

The unrolled tick is the class's short path (``_short_path`` in
:mod:`ordered`) written out: it applies when the
walk starts at the first child, nobody listens to status changes and no
pre/post conditions are attached, and ends on a child returning RUNNING or
``STOP`` after children that all returned ``NEXT``, or with every child
returning ``NEXT``. Anything else is handed to the class's general ``_walk``
or ``_tail``, as the shared short path does, so the observable behaviour is
the same (the conformance suite runs both).

The code for a (kind, number of children) is compiled once; each node gets a
copy of that code object (its own inline caches) bound with
:class:`types.FunctionType` over a fresh globals dict holding its children.
"""

from __future__ import annotations

import types
from functools import cache
from typing import Any

from aiobt.core.node import TreeNode
from aiobt.core.status import IDLE, RUNNING

MAX_CHILDREN = 12  # beyond this the shared loop is used (the code grows with the children)
INLINE = 4  # at most this many resets are written out per branch; more loop in a helper


def _reset_lines(indent: str, first: int, count: int, inline: int = INLINE) -> list[str]:
    """Reset children ``first`` to ``count - 1``: a RUNNING one is halted, the
    others set IDLE in place (as ``reset_all``/``_reset`` do when nobody
    listens); by a loop in :func:`reset_from` if there are more than ``inline``."""
    if count - first > inline:
        return [f"{indent}RESET_FROM(self.children, {first})"]
    lines = []
    for i in range(first, count):
        lines.append(f"{indent}if c{i}._status is RUNNING:")
        lines.append(f"{indent}    c{i}.halt_sync()")
        lines.append(f"{indent}else:")
        lines.append(f"{indent}    c{i}._status = IDLE")
    return lines


def reset_from(children: list[TreeNode], first: int) -> None:
    """Reset ``children[first:]`` when nobody listens: halt a RUNNING one, set
    the others IDLE in place (the loop behind :func:`_reset_lines`)."""
    for child in children[first:] if first else children:
        if child._status is RUNNING:
            child.halt_sync()
        else:
            child._status = IDLE


@cache
def _code(reactive: bool, count: int) -> types.CodeType:
    """The unrolled tick for ``count`` children, as a code object."""
    guard = "self._conditions is not None or CTX.listeners"
    if not reactive:
        guard = "self._current or " + guard
    lines = ["def tick_sync(self):", f"    if {guard}:", "        return WALK(self)"]
    for i in range(count):
        lines.append(f"    status = c{i}.tick_sync()")
        lines.append("    if status is not NEXT:")
        lines.append("        if status is RUNNING:")
        if reactive:  # the children before it returned NEXT; a later one may be RUNNING
            lines.extend(f"            c{j}._status = IDLE" for j in range(i))
            lines.extend(_reset_lines("            ", i + 1, count))
        elif i:
            lines.append(f"            self._current = {i}")
        lines.append("            self._status = RUNNING")
        lines.append("            return RUNNING")
        lines.append("        if status is not STOP:")
        lines.append(f"            return TAIL(self, c{i}, status)")
        lines.extend(_reset_lines("        ", 0, count))
        lines.append("        self._status = STOP")
        lines.append("        return STOP")
    lines.extend(_reset_lines("    ", 0, count, count))  # (once per tick: written out)
    lines.append("    self._status = NEXT")
    lines.append("    return NEXT")
    source = "\n".join(lines) + "\n"
    kind = "reactive" if reactive else "ordered"
    namespace: dict[str, Any] = {}
    exec(compile(source, f"<aiobt unrolled {kind} tick, {count} children>", "exec"), namespace)
    code: types.CodeType = namespace["tick_sync"].__code__
    return code


def unroll(node: Any, reactive: bool) -> bool:
    """Give ``node`` (a ``WalkedComposite`` of :mod:`.ordered`, ``reactive`` or not) its
    unrolled tick; False (and unchanged) if it does not apply.

    It applies when the node's class's tick is the short path built for it (not a
    subclass's own ``tick_sync``, not the yielding variants) with 1 to
    :data:`MAX_CHILDREN` children, once.
    """
    cls = type(node)
    children = node.children
    if (
        cls.__dict__.get("_UNROLLED", False)
        or getattr(cls.tick_sync, "walk", None) is not cls._walk
        or not 0 < len(children) <= MAX_CHILDREN
    ):
        return False
    scope: dict[str, Any] = {f"c{i}": child for i, child in enumerate(children)}
    scope.update(
        CTX=node._ctx,
        WALK=cls._walk,
        TAIL=cls._tail,
        NEXT=cls.NEXT,
        STOP=cls.STOP,
        RUNNING=RUNNING,
        IDLE=IDLE,
        RESET_FROM=reset_from,
        __builtins__={},
    )
    # a copy of the code per node: its own inline caches, each site seeing one type
    code = _code(reactive, len(children)).replace()
    namespace: dict[str, Any] = {
        "__slots__": (),
        "__module__": cls.__module__,
        "__qualname__": cls.__qualname__,
        "__doc__": cls.__doc__,
        "_UNROLLED": True,
        "tick_sync": types.FunctionType(code, scope, "tick_sync"),
        "execute_sync": cls.execute_sync,
    }
    node.__class__ = type(cls.__name__, (cls,), namespace)
    return True


def reroll(node: Any) -> None:
    """Undo :func:`unroll` (the node's children are about to change)."""
    cls = type(node)
    if cls.__dict__.get("_UNROLLED", False):
        node.__class__ = cls.__bases__[0]
