"""The four benchmark shapes, described once and built for every library.

A :class:`Spec` is a node: a control/decorator ID with children, or one of the
four stub leaves. The same spec becomes BT.CPP v4 XML (aiobt and
behaviortreepy load the same text), a py_trees tree, and the await floor.

Stub leaves (same behaviour in every library):

- ``OkAction``: a sync action returning SUCCESS;
- ``OkCondition`` / ``FailCondition``: a condition returning SUCCESS / FAILURE;
- ``RunAction``: a stateful action returning RUNNING on start and on every tick.
"""

from __future__ import annotations

from dataclasses import dataclass

LEAVES = ("OkAction", "OkCondition", "FailCondition", "RunAction")


@dataclass(frozen=True, slots=True)
class Spec:
    kind: str
    children: tuple[Spec, ...] = ()
    name: str = ""
    attrs: tuple[tuple[str, str], ...] = ()

    @property
    def is_leaf(self) -> bool:
        return self.kind in LEAVES


def node(kind: str, *children: Spec, name: str = "", **attrs: str) -> Spec:
    return Spec(kind, children, name, tuple(attrs.items()))


def leaf(kind: str, name: str = "") -> Spec:
    assert kind in LEAVES, kind
    return Spec(kind, (), name)


def wide_sequence(width: int = 1000) -> Spec:
    """One Sequence over ``width`` SUCCESS actions: width + 1 node-ticks per tick."""
    return node("Sequence", *(leaf("OkAction") for _ in range(width)))


def deep_nesting(depth: int = 100) -> Spec:
    """``depth`` nested Sequences over one SUCCESS action: depth + 1 node-ticks."""
    spec = leaf("OkAction")
    for _ in range(depth):
        spec = node("Sequence", spec)
    return spec


def reactive_running(conditions: int = 10) -> Spec:
    """ReactiveSequence of SUCCESS conditions over a RUNNING action."""
    return node(
        "ReactiveSequence",
        *(leaf("OkCondition") for _ in range(conditions)),
        leaf("RunAction"),
    )


def _recovery(main: Spec, recovery: Spec, name: str) -> Spec:
    # Nav2's RecoveryNode: while `main` runs or succeeds only `main` is ticked,
    # which a Fallback reproduces visit for visit.
    return node("Fallback", main, recovery, name=name)


def nav2_navigate_to_pose() -> Spec:
    """navigate_to_pose_w_replanning_and_recovery.xml with built-in nodes and stubs.

    PipelineSequence -> ReactiveSequence (re-ticks the earlier children each
    tick), RecoveryNode -> Fallback, RateController -> RetryUntilSuccessful
    num_attempts=1 (pass-through, i.e. replanning checked every tick), RoundRobin
    -> Fallback; Nav2 leaves -> stubs. Steady state: following a path (FollowPath
    RUNNING), no new path needed (CheckIfNewPathNeeded succeeds).
    """
    check_path = node(
        "ReactiveSequence",
        node("Inverter", leaf("FailCondition", "GlobalUpdatedGoal")),
        leaf("OkCondition", "IsGoalNearby"),
        leaf("OkAction", "TruncatePathLocal"),
        leaf("OkCondition", "ValidatePath"),
        name="CheckIfNewPathNeeded",
    )
    planner_recovery = node(
        "Sequence", leaf("OkCondition", "WouldAPlannerRecoveryHelp"), leaf("OkAction", "Clear")
    )
    compute_path = _recovery(
        node("Fallback", check_path, leaf("RunAction", "ComputePathToPose")),
        planner_recovery,
        "ComputePathToPose",
    )
    controller_recovery = node(
        "Sequence", leaf("OkCondition", "WouldAControllerRecoveryHelp"), leaf("OkAction", "Clear")
    )
    pipeline = node(
        "ReactiveSequence",
        *(leaf("OkAction", f"{what}Selector") for what in _SELECTORS),
        node("RetryUntilSuccessful", compute_path, name="RateController", num_attempts="1"),
        _recovery(leaf("RunAction", "FollowPath"), controller_recovery, "FollowPath"),
        name="NavigateWithReplanning",
    )
    recoveries = node(
        "Sequence",
        node("Fallback", leaf("FailCondition"), leaf("FailCondition")),
        node(
            "ReactiveFallback",
            leaf("FailCondition", "GoalUpdated"),
            node(
                "Fallback",
                node("Sequence", leaf("OkAction"), leaf("OkAction"), name="ClearingActions"),
                leaf("RunAction", "Spin"),
                leaf("RunAction", "Wait"),
                leaf("RunAction", "BackUp"),
                name="RoundRobin",
            ),
        ),
    )
    return _recovery(pipeline, recoveries, "NavigateRecovery")


_SELECTORS = ("ProgressChecker", "GoalChecker", "PathHandler", "Controller", "Planner")

SHAPES = {
    "seq1000": wide_sequence,
    "deep100": deep_nesting,
    "reactive10": reactive_running,
    "nav2": nav2_navigate_to_pose,
}


def to_xml(spec: Spec) -> str:
    """BT.CPP v4 XML with one tree, ``Main``."""
    return (
        '<root BTCPP_format="4" main_tree_to_execute="Main">'
        f'<BehaviorTree ID="Main">{_element(spec)}</BehaviorTree></root>'
    )


def _element(spec: Spec) -> str:
    attrs = "".join(f' {key}="{value}"' for key, value in spec.attrs)
    if spec.name:
        attrs += f' name="{spec.name}"'
    if not spec.children:
        return f"<{spec.kind}{attrs}/>"
    inner = "".join(_element(child) for child in spec.children)
    return f"<{spec.kind}{attrs}>{inner}</{spec.kind}>"
