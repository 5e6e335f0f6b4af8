"""aiobt inside your own asyncio program (run `.venv/bin/aiobt up --world small` first).

    .venv/bin/python examples/embedded.py    # --connect tcp/127.0.0.1:7447 --namespace robot

1. Ticks a small Nav2 tree of its own (plan with ComputePathToPose, drive
   with FollowPath) in this program, next to another task of the program.
2. Sends a goal to the navigator and follows its feedback.
Exit status 0 when both reach their goals.
"""

from __future__ import annotations

import argparse
import asyncio

from aiobt import Status
from aiobt.embed import NavigationOutcome, RobotClient, connect
from aiobt.transport import ActionError

TREE = """
<root BTCPP_format="4">
  <BehaviorTree ID="PlanAndDrive">
    <Sequence>
      <ComputePathToPose goal="{goal}" path="{path}" planner_id="GridBased"/>
      <FollowPath path="{path}" controller_id="FollowPath"/>
    </Sequence>
  </BehaviorTree>
</root>
"""


async def heartbeat(robot: RobotClient, stop: asyncio.Event) -> int:
    """The program's own work, running while the tree ticks: here, count clock seconds."""
    beats = 0
    while not stop.is_set():
        await robot.clock.sleep(1.0)
        beats += 1
    return beats


async def main(args: argparse.Namespace) -> int:
    print(f"connecting to {args.connect}, namespace {args.namespace}", flush=True)
    async with connect(args.namespace, args.connect, sim_time=args.sim_time) as robot:
        # 1. a tree of our own, ticked here: Nav2's nodes talk to the planner and controller
        print("own tree: planning and driving to (0.8, 0.6)...", flush=True)
        tree = robot.load_tree(TREE, goal="0.8;0.6;0.0")
        stop = asyncio.Event()
        beating = asyncio.create_task(heartbeat(robot, stop))
        status = await tree.tick_while_running(period=0.02)
        stop.set()
        print(f"own tree: {status.name} ({await beating} s of heartbeat meanwhile)")

        # 2. a goal for the navigator, which runs Nav2's full tree with recoveries
        shown = [-1.0]  # robot time of the last line: one a second

        def show(feedback: object) -> None:
            if robot.clock.now() - shown[0] >= 1.0:
                shown[0] = robot.clock.now()
                print(f"  {getattr(feedback, 'distance_remaining', 0.0):.2f} m to go", flush=True)

        print("navigator: driving to (-0.5, -0.5)...", flush=True)

        try:
            outcome: NavigationOutcome = await robot.navigate_to(-0.5, -0.5, 0.0, on_feedback=show)
        except ActionError as exc:  # no navigator, goal rejected, or the navigator went away
            print(f"navigator: {exc}")
            return 1
        error = f" error {outcome.error_code} {outcome.error_msg}" if outcome.error_code else ""
        print(f"navigator: {outcome.state.name}{error}")
    return 0 if status is Status.SUCCESS and outcome.succeeded else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--connect", default="tcp/127.0.0.1:7447")
    parser.add_argument("--namespace", default="robot")
    parser.add_argument("--sim-time", action="store_true", help="the system runs at a speed-up")
    raise SystemExit(asyncio.run(main(parser.parse_args())))
