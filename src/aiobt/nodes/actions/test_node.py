"""The node a substitution rule puts in place of a real one (BT.CPP's TestNode)."""

from __future__ import annotations

from aiobt.core.leaves import AsyncActionNode
from aiobt.core.manifest import NodeBuilder, TestNodeConfig
from aiobt.core.node import NodeConfig, TreeNode
from aiobt.core.status import Status


class TestNode(AsyncActionNode):
    """Returns the configured status after the configured clock delay; then
    runs the configured ``on_complete`` callback. Its ports are those of the
    node it replaces, so the XML is validated as written."""

    __slots__ = ("test_config",)
    __test__ = False  # not a pytest test class

    def __init__(self, name: str, config: NodeConfig, test_config: TestNodeConfig) -> None:
        super().__init__(name, config)
        self.test_config = test_config

    async def run(self) -> Status:
        spec = self.test_config
        if spec.delay > 0:
            await self.clock.sleep(spec.delay)
        if spec.on_complete is not None:
            spec.on_complete(self)
        return spec.status


def test_node_builder(spec: TestNodeConfig) -> NodeBuilder:
    def build(name: str, config: NodeConfig) -> TreeNode:
        return TestNode(name, config, spec)

    return build


test_node_builder.__test__ = False  # type: ignore[attr-defined]
