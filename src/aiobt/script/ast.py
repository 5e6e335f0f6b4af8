"""The syntax tree of a script; :mod:`aiobt.script.compiler` turns it into closures."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True, slots=True)
class Literal:
    value: Any
    column: int


@dataclass(frozen=True, slots=True)
class Name:
    name: str
    column: int


@dataclass(frozen=True, slots=True)
class Unary:
    op: str
    operand: Expr
    column: int


@dataclass(frozen=True, slots=True)
class Binary:
    op: str
    left: Expr
    right: Expr
    column: int


@dataclass(frozen=True, slots=True)
class Compare:
    """A chain ``a < b <= c``: true when every adjacent pair holds."""

    ops: tuple[str, ...]
    operands: tuple[Expr, ...]
    column: int


@dataclass(frozen=True, slots=True)
class Ternary:
    condition: Expr
    then: Expr
    otherwise: Expr
    column: int


@dataclass(frozen=True, slots=True)
class Assign:
    op: str
    key: str
    value: Expr
    column: int


Expr = Literal | Name | Unary | Binary | Compare | Ternary | Assign
