"""Per-node statistics (real tick counts) and the unicode tree display."""

from __future__ import annotations

from aiobt.core.status import Status
from aiobt.display import render
from aiobt.loggers import TreeStatistics
from aiobt.testing.stubs import Stubs, tree_xml

BODY = """
<Sequence>
  <StubCondition name="Check"/>
  <StubAction name="Go"/>
  <Inverter><AlwaysFailure name="Never"/></Inverter>
</Sequence>"""


async def test_statistics_count_ticks_results_and_restore_classes() -> None:
    stubs = Stubs()
    stubs.script("Go", "RUNNING", "RUNNING", "SUCCESS", "FAILURE")
    tree = stubs.factory().create_tree_from_text(tree_xml(BODY))
    classes = [type(n) for n in tree.nodes()]
    stats = TreeStatistics(tree)
    for _ in range(4):
        await tree.tick_exactly_once()
    go = stats["Go"]
    assert (go.ticks, go.running, go.successes, go.failures) == (4, 2, 1, 1)
    assert go.last_status is Status.FAILURE
    assert go.last_result is Status.FAILURE
    assert go.transitions == 3  # ->RUNNING, ->SUCCESS, ->FAILURE (RUNNING twice is no change)
    check = stats["Check"]
    assert (check.ticks, check.successes) == (2, 2)  # a Sequence does not re-check
    assert stats["MainTree/Sequence"].ticks == 4
    assert stats[1] is stats["MainTree/Sequence"]
    never = stats["Never"]
    assert (never.ticks, never.failures) == (1, 1)
    assert stubs.ticks("Go") == 4  # the instrumented nodes still behave
    stats.close()
    assert [type(n) for n in tree.nodes()] == classes
    await tree.tick_exactly_once()
    assert stats["Go"].ticks == 4  # no counting once closed


async def test_statistics_count_skips() -> None:
    stubs = Stubs()
    stubs.script("Go", "SKIPPED")
    body = '<Sequence><StubAction name="Go"/><AlwaysSuccess name="Done"/></Sequence>'
    tree = stubs.factory().create_tree_from_text(tree_xml(body))
    with TreeStatistics(tree) as stats:
        await tree.tick_exactly_once()
        await tree.tick_exactly_once()
    assert (stats["Go"].ticks, stats["Go"].skips, stats["Go"].transitions) == (2, 2, 0)
    assert stats["Done"].successes == 2


async def test_display_renders_statuses() -> None:
    stubs = Stubs()
    stubs.script("Go", "RUNNING")
    tree = stubs.factory().create_tree_from_text(tree_xml(BODY))
    await tree.tick_exactly_once()
    assert render(tree) == "\n".join(
        [
            "◐ Sequence [RUNNING]",
            '├── ✔ StubCondition "Check" [SUCCESS]',
            '├── ◐ StubAction "Go" [RUNNING]',
            "└── ○ Inverter [IDLE]",
            '    └── ○ AlwaysFailure "Never" [IDLE]',
        ]
    )
    with TreeStatistics(tree) as stats:
        await tree.tick_exactly_once()
        text = render(tree.root, stats=stats, color=True)
    assert '\x1b[33m◐ StubAction "Go" [RUNNING] ticks=1 ok=0 fail=0\x1b[0m' in text
