"""A recursive-descent parser for BT.CPP 4.8's script grammar.

Precedence, lowest first (as BT.CPP's lexy grammar):

1. assignment ``:= = += -= *= /=`` (not chainable; the left side is a key);
2. ternary ``c ? x : y`` (not chainable without parentheses; ``x`` may be any
   expression, ``y`` a logical one);
3. ``&&`` and ``||``, one level, left to right;
4. comparisons ``== != < > <= >=``, chainable: ``1 < x < 5``;
5. operands: arithmetic ``+ -`` over ``* /`` over unary ``-``; bitwise
   ``| ^`` over ``&`` over unary ``~ !``; string ``..``. One expression uses
   one of these three families, across its comparisons, ``&&``/``||`` and the
   ``else`` part of a ternary; parentheses (and the middle of a ternary) start
   a new expression. ``1 + 1 == 2 & 2`` is an error, as in BT.CPP.

BT.CPP 4.8 groups ``+ -`` and ``* /`` from the right: ``5 - 2 + 1`` is
``5 - (2 + 1)`` = 2 there; this parser does the same, so scripts give the same
numbers under aiobt and BT.CPP (use parentheses to be explicit).
"""

from __future__ import annotations

from aiobt.script.ast import Assign, Binary, Compare, Expr, Literal, Name, Ternary, Unary
from aiobt.script.errors import ScriptSyntaxError
from aiobt.script.lexer import END, NAME, NUMBER, OP, STRING, Token, tokenize

ASSIGN_OPS = frozenset({":=", "=", "+=", "-=", "*=", "/="})
COMPARE_OPS = frozenset({"==", "!=", "<", ">", "<=", ">="})
LOGIC_OPS = frozenset({"&&", "||"})

# operator family of each group operator: operands of one comparison use one family
FAMILY = {
    "+": "arithmetic", "-": "arithmetic", "*": "arithmetic", "/": "arithmetic",
    "|": "bitwise", "^": "bitwise", "&": "bitwise", "~": "bitwise", "!": "bitwise",
    "..": "string",
}  # fmt: skip
# binary levels inside a group, loosest first; True = right-associative (BT.CPP's quirk)
LEVELS: tuple[dict[str, bool], ...] = (
    {"+": True, "-": True, "|": False, "^": False, "..": False},
    {"*": True, "/": True, "&": False},
)
PREFIX = frozenset({"-", "~", "!"})
MAX_NESTING = 64


MAX_DEPTH = 200


def parse(script: str) -> list[Expr]:
    """The statements of ``script`` (separated by ``;``)."""
    try:
        statements = _Parser(script).statements()
        deepest = max(_depth(expr) for expr in statements)
    except RecursionError:
        deepest = MAX_DEPTH + 1
    if deepest > MAX_DEPTH:
        raise ScriptSyntaxError(f"script too deeply nested (over {MAX_DEPTH} levels)", script, 1)
    return statements


def _depth(expr: Expr) -> int:
    if isinstance(expr, Unary):
        return 1 + _depth(expr.operand)
    if isinstance(expr, Binary):
        return 1 + max(_depth(expr.left), _depth(expr.right))
    if isinstance(expr, Compare):
        return 1 + max(_depth(e) for e in expr.operands)
    if isinstance(expr, Ternary):
        return 1 + max(_depth(e) for e in (expr.condition, expr.then, expr.otherwise))
    if isinstance(expr, Assign):
        return 1 + _depth(expr.value)
    return 1


class _Parser:
    def __init__(self, script: str) -> None:
        self.script = script
        self.tokens = tokenize(script)
        self.pos = 0
        self.family: str | None = None
        self.depth = 0

    # -- helpers ----------------------------------------------------------------
    @property
    def token(self) -> Token:
        return self.tokens[self.pos]

    def error(self, message: str, token: Token | None = None) -> ScriptSyntaxError:
        column = (token or self.token).column
        return ScriptSyntaxError(message, self.script, column)

    def take(self) -> Token:
        token = self.tokens[self.pos]
        self.pos += 1
        return token

    def at_op(self, ops: frozenset[str] | dict[str, bool] | str) -> bool:
        token = self.token
        if token.kind != OP:
            return False
        return token.text == ops if isinstance(ops, str) else token.text in ops

    # -- statements ---------------------------------------------------------------
    def statements(self) -> list[Expr]:
        if self.token.kind == END:
            raise self.error("empty script")
        result = [self.expression()]
        while self.at_op(";"):
            separator = self.take()
            if self.token.kind == END:
                raise self.error("unexpected trailing ';'", separator)
            result.append(self.expression())
        if self.token.kind != END:
            raise self.error(f"expected ';' before {self.token.text!r}")
        return result

    def expression(self) -> Expr:
        if self.depth >= MAX_NESTING:
            raise self.error(f"expression nested more than {MAX_NESTING} levels deep")
        saved, self.family = self.family, None
        self.depth += 1
        try:
            return self.assignment()
        finally:
            self.family = saved
            self.depth -= 1

    def assignment(self) -> Expr:
        left = self.ternary()
        if not self.at_op(ASSIGN_OPS):
            return left
        op = self.take()
        if not isinstance(left, Name):
            raise self.error(f"the left side of [{op.text}] must be a blackboard key", op)
        value = self.ternary()
        if self.at_op(ASSIGN_OPS):
            raise self.error("assignments cannot be chained; use ';' between them")
        return Assign(op.text, left.name, value, op.column)

    def ternary(self) -> Expr:
        condition = self.logical()
        if not self.at_op("?"):
            return condition
        mark = self.take()
        then = self.expression()
        if not self.at_op(":"):
            raise self.error("expected ':' of the ternary operator")
        self.take()
        otherwise = self.logical()
        if self.at_op("?"):
            raise self.error("ternary operators cannot be chained without parentheses")
        return Ternary(condition, then, otherwise, mark.column)

    def logical(self) -> Expr:
        left = self.comparison()
        while self.at_op(LOGIC_OPS):
            op = self.take()
            left = Binary(op.text, left, self.comparison(), op.column)
        return left

    def comparison(self) -> Expr:
        first = self.group()
        if not self.at_op(COMPARE_OPS):
            return first
        column = self.token.column
        ops: list[str] = []
        operands = [first]
        while self.at_op(COMPARE_OPS):
            ops.append(self.take().text)
            operands.append(self.group())
        return Compare(tuple(ops), tuple(operands), column)

    # -- operands of comparisons: one operator family per expression -----------
    def group(self) -> Expr:
        return self.binary(0)

    def use_family(self, token: Token) -> None:
        family = FAMILY[token.text]
        if self.family is None:
            self.family = family
        elif self.family != family:
            raise self.error(
                f"operator [{token.text}] ({family}) cannot be mixed with the "
                f"{self.family} operators before it; add parentheses",
                token,
            )

    def binary(self, level: int) -> Expr:
        if level == len(LEVELS):
            return self.unary()
        ops = LEVELS[level]
        left = self.binary(level + 1)
        while self.at_op(ops):
            op = self.take()
            self.use_family(op)
            if ops[op.text]:  # right-associative
                return Binary(op.text, left, self.binary(level), op.column)
            left = Binary(op.text, left, self.binary(level + 1), op.column)
        return left

    def unary(self) -> Expr:
        ops = []
        while self.at_op(PREFIX):
            op = self.take()
            self.use_family(op)
            ops.append(op)
        expr = self.atom()
        for op in reversed(ops):
            expr = Unary(op.text, expr, op.column)
        return expr

    def atom(self) -> Expr:
        token = self.token
        if token.kind == NUMBER or token.kind == STRING:
            self.take()
            return Literal(token.value, token.column)
        if token.kind == NAME:
            self.take()
            if token.text in ("true", "false"):
                return Literal(1 if token.text == "true" else 0, token.column)
            return Name(token.text, token.column)
        if token.kind == OP and token.text == "(":
            self.take()
            inner = self.expression()
            if not self.at_op(")"):
                raise self.error("expected ')'")
            self.take()
            return inner
        if token.kind == OP and token.text == "+":
            return self.signed_literal()
        raise self.error("expected an operand" if token.kind != END else "unexpected end of script")

    def signed_literal(self) -> Expr:
        sign = self.take()
        number = self.token
        if number.kind != NUMBER or number.spaced:
            raise self.error("expected a number right after '+'", sign)
        self.take()
        return Literal(number.value, sign.column)
