"""Nav2's ';'-separated strings as BT port literals: poses, paths and goals typed ports
read XML text through the real loader, and render back to the same text."""

from __future__ import annotations

import math
from typing import Any, ClassVar

import pytest

from aiobt.core.convert import to_text, type_name
from aiobt.core.errors import TreeLoadError
from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import Goals, Header, Path, Point, PoseStamped, Quaternion
from aiobt.testing.stubs import tree_xml


class GoTo(SyncActionNode):
    """Records what its typed ports read."""

    seen: ClassVar[dict[str, Any]] = {}
    PORTS = (
        input_port("goal", PoseStamped),
        input_port("path", Path, "0;map"),
        input_port("goals", Goals, ""),
        input_port("target", Point, Point()),
        input_port("heading", Quaternion, "0;0;0;1"),
    )

    def on_tick(self) -> Status:
        for name in ("goal", "path", "goals", "target", "heading"):
            GoTo.seen[name] = self.get_input(name)
        return Status.SUCCESS


@pytest.fixture
def factory() -> BehaviorTreeFactory:
    GoTo.seen = {}
    factory = BehaviorTreeFactory()
    factory.register_node_type(GoTo)
    return factory


async def _tick(factory: BehaviorTreeFactory, attributes: str) -> dict[str, Any]:
    tree = factory.create_tree_from_text(tree_xml(f"<GoTo {attributes}/>"))
    assert await tree.tick_exactly_once() is Status.SUCCESS
    return GoTo.seen


async def test_a_short_pose_literal_is_a_pose_stamped_in_map(factory: BehaviorTreeFactory) -> None:
    seen = await _tick(factory, 'goal="1.0;2.0;0.5"')
    goal = seen["goal"]
    assert isinstance(goal, PoseStamped)
    assert (goal.x, goal.y, goal.header.frame_id) == (1.0, 2.0, "map")
    assert goal.yaw == pytest.approx(0.5)
    assert seen["path"] == Path(header=Header(frame_id="map"))  # the text default, converted
    assert seen["target"] == Point()


async def test_nav2_nine_field_pose_and_the_other_types(factory: BehaviorTreeFactory) -> None:
    pose = "1500000000;odom;1.0;-2.0;0.0;0.0;0.0;0.0;1.0"
    seen = await _tick(
        factory,
        f'goal="{pose}" path="3000000000;map;{pose};{pose}" goals="0;map;{pose}" '
        'target="1;2;3" heading="0;0;0.7071068;0.7071068"',
    )
    goal = seen["goal"]
    assert (goal.header.stamp, goal.header.frame_id, goal.x, goal.y) == (1.5, "odom", 1.0, -2.0)
    path = seen["path"]
    assert isinstance(path, Path)
    assert (path.header.stamp, path.header.frame_id) == (3.0, "map")
    assert path.poses == [goal, goal]
    assert isinstance(seen["goals"], Goals)
    assert seen["goals"].goals == [goal]
    assert seen["target"] == Point(x=1, y=2, z=3)
    assert seen["heading"].yaw == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(
    ("attributes", "fragments"),
    [
        ('goal="1.0;abc;0.5"', ["[goal]", "'y'", "not a number"]),
        ('goal="1;2"', ["[goal]", "expected 9, 7 or 3 fields"]),
        ('goal="x;map;1;2;0;0;0;0;1"', ["[goal]", "header.stamp"]),
        ('goal="0;map;1;2;0;0;0;0;0"', ["[goal]", "pose.orientation", "unit length"]),
        ('goal="1;2;0" path="0;map;1;2"', ["[path]", "9 fields per pose"]),
        ('goal="1;2;0" goals="0;map;1;2;inf;0;0;0;1"', ["[goals]", "pose.position.z", "finite"]),
        ('goal="1;2;0" target="1;2;nan"', ["[target]", "'z'", "finite"]),
    ],
)
def test_a_bad_literal_names_the_port_and_the_field(
    factory: BehaviorTreeFactory, attributes: str, fragments: list[str]
) -> None:
    with pytest.raises(TreeLoadError) as caught:
        factory.create_tree_from_text(tree_xml(f"<GoTo {attributes}/>"))
    for fragment in fragments:
        assert fragment in caught.value.message
    assert caught.value.node_path == "MainTree/GoTo"


async def test_to_text_gives_the_nav2_string_that_reads_back_equal(
    factory: BehaviorTreeFactory,
) -> None:
    pose = PoseStamped.from_xy_yaw(1.25, -3.5, 2.0, frame_id="odom", stamp=0.3)
    path = Path(header=Header(stamp=7.1, frame_id="map"), poses=[pose, pose])
    goals = Goals(header=Header(stamp=2.5, frame_id="odom"), goals=[pose])
    texts = {name: to_text(value) for name, value in (("goal", pose), ("path", path))}
    assert texts["goal"].split(";")[:2] == ["300000000", "odom"]
    assert len(texts["goal"].split(";")) == 9
    attributes = " ".join(f'{name}="{text}"' for name, text in texts.items())
    seen = await _tick(factory, f'{attributes} goals="{to_text(goals)}"')
    assert seen["goal"] == pose
    assert seen["path"] == path
    assert seen["goals"] == goals
    assert to_text(Point(x=1, y=2, z=3)) == "1.0;2.0;3.0"


async def test_a_text_on_a_typed_blackboard_entry_is_converted(
    factory: BehaviorTreeFactory,
) -> None:
    tree = factory.create_tree_from_text(tree_xml('<GoTo goal="{goal}"/>'))
    tree.root_blackboard.set("goal", "4;5;0")
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert (GoTo.seen["goal"].x, GoTo.seen["goal"].y) == (4.0, 5.0)


def test_the_nodes_model_names_nav2_types(factory: BehaviorTreeFactory) -> None:
    names = {type_name(tp) for tp in (PoseStamped, Path, Goals, Point, Quaternion)}
    assert names == {
        "geometry_msgs::msg::PoseStamped",
        "nav_msgs::msg::Path",
        "nav_msgs::msg::Goals",
        "geometry_msgs::msg::Point",
        "geometry_msgs::msg::Quaternion",
    }
    model = factory.tree_nodes_model_xml()
    assert 'type="geometry_msgs::msg::PoseStamped"' in model
    assert 'default="0.0;0.0;0.0"' in model  # the Point() default, as Nav2 text
