"""BehaviorTree.CPP 4.8's script language: ``a := 1; b = a + 2 > 3 ? 'x' : 'y'``.

>>> from aiobt.core.blackboard import Blackboard
>>> bb = Blackboard.create()
>>> compile_script("n := 3; msg := 'n=' .. n")(bb)
'n=3'

See ``docs/scripting.md`` for the grammar, the value rules and where aiobt
differs from BT.CPP.
"""

from aiobt.script.errors import ScriptError, ScriptSyntaxError
from aiobt.script.script import Script, compile_condition, compile_script, run_script
from aiobt.script.values import truth

__all__ = [
    "Script",
    "ScriptError",
    "ScriptSyntaxError",
    "compile_condition",
    "compile_script",
    "run_script",
    "truth",
]
