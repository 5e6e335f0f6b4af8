"""Tokens of BT.CPP's script language, each with its 1-based column.

Numbers follow BT.CPP's grammar: ``0x1F`` hex and ``42`` integers, ``1.5``,
``2e3`` and ``1.5e-3`` reals; a number directly followed by a letter, ``_``
or ``.`` is an error (``1.`` and ``3px`` are rejected as in BT.CPP). Strings
are single- or double-quoted, without escapes. Names start with a letter,
``_`` or ``@`` (root blackboard) and go on with letters, digits and ``_``.
"""

from __future__ import annotations

from dataclasses import dataclass

from aiobt.script.errors import ScriptSyntaxError

INT64_MAX = 2**63 - 1

# longest first, so ":=" wins over ":" and "==" over "="
OPERATORS = (
    ":=", "+=", "-=", "*=", "/=", "==", "!=", "<=", ">=", "&&", "||", "..",
    "=", "<", ">", "&", "|", "^", "~", "!", "+", "-", "*", "/", "?", ":", "(", ")", ";",
)  # fmt: skip

NUMBER, STRING, NAME, OP, END = "number", "string", "name", "op", "end"


@dataclass(frozen=True, slots=True)
class Token:
    kind: str
    text: str
    column: int
    value: object = None
    spaced: bool = True  # whitespace (or the start) right before this token


def tokenize(script: str) -> list[Token]:
    """The tokens of ``script``, ending with an END token."""
    tokens: list[Token] = []
    pos, size = 0, len(script)
    spaced = True
    while pos < size:
        char = script[pos]
        if char.isspace() or (char == "\\" and script[pos + 1 : pos + 2] in ("\n", "\r")):
            pos += 1
            spaced = True
            continue
        token, pos = _token_at(script, pos)
        tokens.append(Token(token.kind, token.text, token.column, token.value, spaced))
        spaced = False
    tokens.append(Token(END, "", size + 1))
    return tokens


def _token_at(script: str, pos: int) -> tuple[Token, int]:
    char = script[pos]
    if char.isdigit():
        return _number(script, pos)
    if char in "'\"":
        end = script.find(char, pos + 1)
        if end < 0:
            raise ScriptSyntaxError(f"missing closing quote {char}", script, pos + 1)
        text = script[pos + 1 : end]
        return Token(STRING, script[pos : end + 1], pos + 1, text), end + 1
    if char == "@" or char == "_" or char.isidentifier():
        end = pos + 1
        while end < len(script) and (script[end] == "_" or script[end].isalnum()):
            end += 1
        name = script[pos:end]
        if name == "@":
            raise ScriptSyntaxError("expected a key name after @", script, pos + 1)
        return Token(NAME, name, pos + 1, name), end
    for op in OPERATORS:
        if script.startswith(op, pos):
            return Token(OP, op, pos + 1), pos + len(op)
    raise ScriptSyntaxError(f"unexpected character {char!r}", script, pos + 1)


def _digits(script: str, pos: int, allowed: str = "0123456789") -> int:
    while pos < len(script) and script[pos] in allowed:
        pos += 1
    return pos


def _number(script: str, start: int) -> tuple[Token, int]:
    if script[start] == "0" and script[start + 1 : start + 2] in ("x", "X"):
        end = _digits(script, start + 2, "0123456789abcdefABCDEF")
        if end == start + 2:
            raise ScriptSyntaxError("expected a hex digit", script, end + 1)
        return _finish_int(script, start, end, int(script[start + 2 : end], 16))
    end = _digits(script, start)
    is_real = False
    if script[end : end + 1] == "." and script[end + 1 : end + 2].isdigit():
        end = _digits(script, end + 1)
        is_real = True
    if script[end : end + 1] in ("e", "E"):
        mark = end + 1
        if script[mark : mark + 1] in ("+", "-"):
            mark += 1
        if script[mark : mark + 1].isdigit():
            end = _digits(script, mark)
            is_real = True
    if not is_real:
        return _finish_int(script, start, end, int(script[start:end]))
    _check_suffix(script, end, "double")
    return Token(NUMBER, script[start:end], start + 1, float(script[start:end])), end


def _finish_int(script: str, start: int, end: int, value: int) -> tuple[Token, int]:
    _check_suffix(script, end, "integer")
    if value > INT64_MAX:
        raise ScriptSyntaxError("integer literal out of range", script, start + 1)
    return Token(NUMBER, script[start:end], start + 1, value), end


def _check_suffix(script: str, end: int, kind: str) -> None:
    nxt = script[end : end + 1]
    if nxt and (nxt == "." or nxt == "_" or nxt.isalpha()):
        if nxt == "." and script[end + 1 : end + 2] == ".":
            raise ScriptSyntaxError(
                f"invalid suffix on {kind} literal (write a space before '..')", script, end + 1
            )
        raise ScriptSyntaxError(f"invalid suffix on {kind} literal", script, end + 1)
