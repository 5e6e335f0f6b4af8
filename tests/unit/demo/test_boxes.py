"""The demo's walled-in leg asks the simulation's own services (``{ns}/sim/srv/obstacles/...``)
for its boxes, waits for the planner's costmap to show them, and takes them away."""

from __future__ import annotations

from aiobt.core.clock import SystemClock
from aiobt.demo.boxes import COSTMAP, INSCRIBED, WALLS, WallIn
from aiobt.msgs import GetCosts
from aiobt.msgs.sim import Ack, RemoveObstacle, SpawnObstacle
from aiobt.transport import Bus
from aiobt.transport.keys import sim_namespace


class World:
    """The robot service's obstacles, and the planner's costmap: lethal once a box is up."""

    def __init__(self) -> None:
        self.boxes: dict[str, SpawnObstacle] = {}

    def spawn(self, box: SpawnObstacle) -> Ack:
        oid = f"box{len(self.boxes)}"
        self.boxes[oid] = box
        return Ack(ok=True, id=oid)

    def remove(self, req: RemoveObstacle) -> Ack:
        return Ack(ok=self.boxes.pop(req.id, None) is not None, id=req.id)

    def costs(self, req: GetCosts.Request) -> GetCosts.Response:
        cost = float(INSCRIBED if len(self.boxes) == len(WALLS) else 0)
        return GetCosts.Response(costs=[cost] * len(req.poses))


async def test_the_boxes_go_up_and_away_through_the_simulation_s_services(
    local_bus: Bus,
) -> None:
    world, sim = World(), sim_namespace(local_bus.namespace)
    local_bus.serve("obstacles/spawn", SpawnObstacle, Ack, world.spawn, namespace=sim)
    local_bus.serve("obstacles/remove", RemoveObstacle, Ack, world.remove, namespace=sim)
    name = GetCosts.service_name(COSTMAP)
    local_bus.serve(name, GetCosts.Request, GetCosts.Response, world.costs)
    walls = WallIn(local_bus, SystemClock())
    placed = await walls.close()
    assert [(x, y, sx, sy) for x, y, _, sx, sy in placed] == list(WALLS)
    assert len(world.boxes) == len(WALLS)
    await walls.open()
    assert not world.boxes
