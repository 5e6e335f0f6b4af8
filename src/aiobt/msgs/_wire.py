"""Validating wire payloads with the models' Python validators off pydantic's path.

Two kinds of Python validator sit on the path of every common message:
- input-form adapters (``before``: a short goal ``{"x", "y", "yaw"}``, a bare
  list of goals); in JSON mode they make pydantic turn the payload into
  Python objects first and validate those, building the message twice;
- in-place checks (``after``: a quaternion has unit length, normalised if
  nearly so), which pydantic calls from Rust once per instance.

At subscription message rates on a shared machine every message meets cold
caches, and these Python calls are a large part of decoding a PoseStamped
(measured in bench/history/transport.md, "third pass"). :func:`wire_validator`
validates the canonical form with a validator built from the model's core
schema without them, into the same model classes, then runs the checks on the
instances they apply to. Whatever that refuses is validated again by the model itself, which
gives the short forms their meaning and every error its usual type, location
and message: results and errors are those of ``model.model_validate_json``.

A validator may be left out only if marked:
- :func:`identity_on_canonical`: a ``before`` validator that returns its
  input unchanged whenever the input validates without it;
- :func:`in_place_check`: an ``after`` validator that returns the instance it
  is given, raising ``ValueError`` or ``AssertionError`` to refuse it.
Checks are moved out only where every instance they apply to is reachable
through fields, lists and optionals, and no other Python validator is left in
the model (one that might read an instance before its check ran); otherwise
they stay in pydantic's path.
"""

from __future__ import annotations

from collections.abc import Callable
from operator import attrgetter
from threading import Lock
from typing import Any, TypeVar, cast

from pydantic import BaseModel
from pydantic_core import CoreConfig, SchemaValidator

M = TypeVar("M", bound=BaseModel)
F = TypeVar("F", bound=Callable[..., Any])
Payload = bytes | bytearray | str
Visit = tuple[Callable[[Any], Any], Callable[[Any], object]]  # (get, check)

_ADAPTERS: set[Callable[..., Any]] = set()
_CHECKS: set[Callable[..., Any]] = set()
_VALIDATORS: dict[type[BaseModel], Callable[[Payload], Any]] = {}
_EACH = object()  # path step: every item of a list
_OPTIONAL = object()  # path step: may be None (then nothing below it to check)
_BUILDING = Lock()
_PYTHON_NODES = {"function-before", "function-after", "function-wrap", "function-plain"}


def identity_on_canonical(fn: F) -> F:
    """Marks a ``before`` validator that returns its input unchanged whenever the input
    validates as the model without it (apply it below ``@classmethod``)."""
    _ADAPTERS.add(fn)
    return fn


def in_place_check(fn: F) -> F:
    """Marks an ``after`` model validator that returns the instance it is given (possibly
    normalised in place) or raises ``ValueError``/``AssertionError``."""
    _CHECKS.add(fn)
    return fn


def wire_validator(model: type[M]) -> Callable[[Payload], M]:
    """``model``'s ``validate_json``, with its marked validators off pydantic's path where
    the input allows; same results, same ``ValidationError`` as the model's own."""
    validate = _VALIDATORS.get(model)
    if validate is None:
        own = getattr(model, "__wire_validate__", None)  # a model that reads non-JSON payloads
        validate = _VALIDATORS[model] = own if own is not None else _build(model)
    return cast(Callable[[Payload], M], validate)


def _build(model: type[BaseModel]) -> Callable[[Payload], Any]:
    full = model.__pydantic_validator__.validate_json
    schema = cast(dict[str, Any], model.__pydantic_core_schema__)
    finder = _CheckFinder(schema)
    checks = finder.visits() if finder.movable else []
    stripped = _ADAPTERS | (_CHECKS if finder.movable else set())
    lean = _strip(schema, stripped)
    if lean is schema:
        return full
    fast = _schema_validator(lean, stripped)
    if fast is None:
        return full
    visits = tuple(checks)

    def validate_json(payload: Payload) -> Any:
        try:
            message = fast(payload)
            for get, check in visits:
                check(get(message))
            return message
        except (ValueError, AssertionError):  # ValidationError is a ValueError
            return full(payload)  # a short form, or bad: the model decides and reports

    return validate_json


def _schema_validator(
    schema: dict[str, Any], stripped: set[Callable[..., Any]]
) -> Callable[[Payload], Any] | None:
    """``validate_json`` of a validator built from ``schema``, or None if pydantic kept one
    of the ``stripped`` validators.

    pydantic-core reuses the validator of a complete model class for every ``model``
    node of that class (its "prebuilt" validator, which holds the validators left out
    here): the schema's model classes are marked incomplete while this validator is
    built, and the result is checked for reused and left-out validators."""
    classes = _model_classes(schema, set())
    with _BUILDING:  # as pydantic's own model_rebuild(force=True) does
        previous = {cls: cls.__dict__.get("__pydantic_complete__") for cls in classes}
        for cls in classes:
            cls.__pydantic_complete__ = False
        try:
            config = cast(CoreConfig | None, schema.get("config"))
            validator = SchemaValidator(schema, config)
        finally:
            for cls, complete in previous.items():
                if complete is None:
                    del cls.__pydantic_complete__  # it was inherited
                else:
                    cls.__pydantic_complete__ = complete
    text = repr(validator)
    if "Prebuilt" in text or any(f"[{fn.__name__}()" in text for fn in stripped):
        return None
    return validator.validate_json


def _model_classes(node: Any, found: set[type[BaseModel]]) -> set[type[BaseModel]]:
    if isinstance(node, dict):
        if node.get("type") == "model":
            found.add(node["cls"])
        for value in node.values():
            _model_classes(value, found)
    elif isinstance(node, list):
        for value in node:
            _model_classes(value, found)
    return found


def _marked(node: dict[str, Any], marks: set[Callable[..., Any]]) -> bool:
    function = node.get("function")
    target = function.get("function") if isinstance(function, dict) else None
    return getattr(target, "__func__", target) in marks


def _strip(node: Any, marks: set[Callable[..., Any]]) -> Any:
    """A copy of the core schema ``node`` without the marked validators (``node`` itself
    when it holds none)."""
    if isinstance(node, dict):
        if node.get("type") in ("function-before", "function-after") and _marked(node, marks):
            inner = _strip(node["schema"], marks)
            if "ref" in node:  # definition-refs name the validator, not what it wraps
                if inner.get("ref", node["ref"]) != node["ref"]:
                    return node  # both named: keep it whole (no such message model)
                inner = {**inner, "ref": node["ref"]}
            return inner
        changed = {key: _strip(value, marks) for key, value in node.items()}
        return node if all(changed[key] is value for key, value in node.items()) else changed
    if isinstance(node, list):
        items = [_strip(value, marks) for value in node]
        return node if all(a is b for a, b in zip(items, node, strict=True)) else items
    return node


class _CheckFinder:
    """Where a core schema's marked checks apply (paths from the message), and whether
    they may be moved out of pydantic's path (see the module docstring)."""

    def __init__(self, schema: dict[str, Any]) -> None:
        self.definitions: dict[str, Any] = {}
        self.found: list[tuple[tuple[object, ...], Callable[..., Any]]] = []
        self.movable = True
        self._collect_definitions(schema)
        self._walk(schema, (), frozenset())

    def visits(self) -> list[Visit]:
        return [_compile(path, check) for path, check in self.found]

    def _collect_definitions(self, node: Any) -> None:
        if isinstance(node, dict):
            if node.get("type") == "definitions":
                for definition in node["definitions"]:
                    self.definitions[definition["ref"]] = definition
            for value in node.values():
                self._collect_definitions(value)
        elif isinstance(node, list):
            for value in node:
                self._collect_definitions(value)

    def _walk(self, node: dict[str, Any], path: tuple[object, ...], refs: frozenset[str]) -> None:
        kind = node.get("type")
        if kind in _PYTHON_NODES:
            if _marked(node, _CHECKS):
                self.found.append((path, node["function"]["function"]))
            elif not _marked(node, _ADAPTERS):
                self.movable = False  # other Python code might see an unchecked instance
            if "schema" in node:
                self._walk(node["schema"], path, refs)
        elif kind == "definition-ref":
            ref = node["schema_ref"]
            if ref in refs or ref not in self.definitions:
                self.movable = False  # recursive (or unknown): no finite set of paths
            else:
                self._walk(self.definitions[ref], path, refs | {ref})
        elif kind == "model":
            if node.get("post_init"):
                self.movable = False
            self._walk(node["schema"], path, refs)
        elif kind == "model-fields":
            for name, field in node["fields"].items():
                self._walk(field["schema"], (*path, name), refs)
        elif kind in ("definitions", "default"):
            if node.get("default_factory_takes_data"):
                self.movable = False
            self._walk(node["schema"], path, refs)
        elif kind == "nullable":
            self._walk(node["schema"], (*path, _OPTIONAL), refs)
        elif kind == "list":
            if "items_schema" in node:
                self._walk(node["items_schema"], (*path, _EACH), refs)
        elif _holds_python(node):
            self.movable = False  # a node kind not followed here, with validators inside


def _holds_python(node: Any) -> bool:
    if isinstance(node, dict):
        if node.get("type") in _PYTHON_NODES or node.get("type") == "definition-ref":
            return True
        return any(_holds_python(value) for value in node.values())
    if isinstance(node, list):
        return any(_holds_python(value) for value in node)
    return False


def _compile(path: tuple[object, ...], check: Callable[..., Any]) -> Visit:
    """``(get, check)``: ``check(get(message))`` checks every instance at ``path`` below a
    message (one attribute chain is read in C, lists and optionals by closures)."""
    split = next((i for i, step in enumerate(path) if not isinstance(step, str)), len(path))
    names = cast(tuple[str, ...], path[:split])
    get: Callable[[Any], Any] = attrgetter(".".join(names)) if names else _same
    if split == len(path):
        return get, check
    below_get, below_check = _compile(path[split + 1 :], check)
    if path[split] is _EACH:

        def each(items: Any) -> None:
            for item in items:
                below_check(below_get(item))

        return get, each

    def optional(value: Any) -> None:
        if value is not None:
            below_check(below_get(value))

    return get, optional


def _same(obj: Any) -> Any:
    return obj
