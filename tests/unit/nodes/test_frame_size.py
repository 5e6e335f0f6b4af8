"""Deep trees recurse through one composite tick per level. CPython 3.11 keeps
frames in 16 KiB data-stack chunks: when a tick's frames outgrow a chunk, every
tick allocates and frees one (deep100 was 2.3x slower for it). These ticks must
keep their frames small: locals, cells and value stack together."""

from __future__ import annotations

import types

import pytest

from aiobt.factory import BehaviorTreeFactory
from aiobt.nodes.control.fallback import Fallback
from aiobt.nodes.control.reactive_sequence import ReactiveSequence
from aiobt.nodes.control.sequence import Sequence

SLOTS = 9  # 101 nested frames of this many slots (+ header) fit in one chunk


def _slots(code: types.CodeType) -> int:
    return code.co_nlocals + len(code.co_cellvars) + len(code.co_freevars) + code.co_stacksize


@pytest.mark.parametrize("cls", [Sequence, Fallback, ReactiveSequence])
def test_the_shared_short_path_frame_is_small(cls: type) -> None:
    assert _slots(cls.__dict__["tick_sync"].__code__) <= SLOTS


@pytest.mark.parametrize("kind", ["Sequence", "Fallback", "ReactiveSequence"])
@pytest.mark.parametrize("children", [1, 2, 12])
def test_an_unrolled_tick_frame_is_small(kind: str, children: int) -> None:
    body = "<AlwaysSuccess/>" * children
    tree = BehaviorTreeFactory().create_tree_from_text(
        f'<root BTCPP_format="4"><BehaviorTree ID="M"><{kind}>{body}</{kind}></BehaviorTree></root>'
    )
    code = type(tree.root).__dict__["tick_sync"].__code__
    assert _slots(code) <= SLOTS
