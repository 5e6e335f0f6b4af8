"""SetBlackboard: write a value (or copy an entry) into a blackboard key."""

from __future__ import annotations

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import blackboard_key, inout_port, input_port
from aiobt.core.status import Status


class SetBlackboard(SyncActionNode):
    """``<SetBlackboard value="42" output_key="answer"/>``.

    ``output_key`` names the entry to write; ``value`` is a literal, or a
    ``{key}`` whose entry is copied (FAILURE if that entry is missing or has
    no value). A typed destination converts the text, as a typed port would.
    """

    __slots__ = ()
    PORTS = (
        input_port(
            "value", None, description="value to be written into the output_key", required=True
        ),
        inout_port(
            "output_key",
            str,
            description="name of the blackboard entry where the value should be written",
            required=True,
        ),
    )

    def on_tick(self) -> Status:
        key = self.get_input("output_key")
        binding = self.config.inputs.get("value")
        if binding is None:
            raise self.logic_error("port [value] is not set")
        bb = self.config.blackboard
        source = binding.key if binding.key is not None else blackboard_key(binding.text, "value")
        if source is not None:
            entry = bb.entry(source)
            if entry is None or not entry.has_value:
                return Status.FAILURE  # BT.CPP: a missing source entry fails too
            if bb.entry(key) is None and entry.type is not None:
                bb.create_entry(key, entry.type)
            bb.set(key, entry.value)
        else:
            bb.set(key, binding.value)
        return Status.SUCCESS
