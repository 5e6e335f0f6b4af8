"""The tree both Groot2 publishers serve in the conformance test.

A Fallback, a SubTree with remapped ports, a RUNNING action (``Slow``: an
async action in aiobt, a stateful action in BT.CPP), and a root blackboard
with an int, a string and a double.
"""

from __future__ import annotations

XML = """<root BTCPP_format="4" main_tree_to_execute="MainTree">
 <BehaviorTree ID="MainTree">
  <Sequence name="main_seq">
    <Fallback name="fb">
      <Check name="check"/>
      <Script name="set_count" code="count := count + 1"/>
    </Fallback>
    <SubTree ID="Work" name="work" goal="{target}" speed="{speed}"/>
    <Check name="after"/>
  </Sequence>
 </BehaviorTree>
 <BehaviorTree ID="Work">
   <Sequence name="work_seq">
     <Script name="local" code="note := 'in work'; goal := 'reached'"/>
     <Slow name="slow"/>
   </Sequence>
 </BehaviorTree>
</root>"""

ENTRIES = {"count": 3, "target": "dock", "speed": 0.5}
