"""Framework Language expressions (paper, section 4.2) and their ontology checks.

Three forms, each an S-expression:

- an instance: ``(AbsolutePositioning :x 10.3 :y -23.67 :yaw 0.23456)``
- attribute access: ``(val Player positioning :playerNumber 5 :whichTeam opp)``
- method execution: ``(exec Player turnToObject :playerNum 3 :whichTeam our :obj (Player ...))``

``parse`` reads text (or an already-read S-expression) into a pydantic model,
:class:`Val` or :class:`Exec`, validating classes, attributes, keys and types;
it raises :class:`~cf_lang.errors.ExpressionError` listing every problem with
its path. ``unparse`` writes any of them back. Sequences are written
``(sequence a b ...)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from functools import cache
from typing import Annotated, Any

from pydantic import BaseModel, TypeAdapter, ValidationError

from .errors import ExpressionError
from .ontology import CLASSES, METHODS, Concept, class_name
from .sexp import Keyword, Symbol, dumps, loads

SEQUENCE = Symbol("sequence")
VAL = Symbol("val")
EXEC = Symbol("exec")
_TRUE, _FALSE = Symbol("true"), Symbol("false")


@dataclass(frozen=True)
class Val:
    """``(val Class attribute :key value ...)``: a reference to an attribute."""

    cls: str
    attribute: str
    key: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Exec:
    """``(exec Class method :key value ... :arg value ...)``: an action request."""

    cls: str
    method: str
    key: dict[str, Any]
    action: Concept


Expression = Concept | Val | Exec


def parse(source) -> Expression:
    """Read and validate one expression from text, bytes or an S-expression."""
    sexp = loads(source) if isinstance(source, (str, bytes, bytearray)) else source
    if not isinstance(sexp, list) or not sexp or type(sexp[0]) is not Symbol:
        raise ExpressionError([("", f"expected (Class ...), (val ...) or (exec ...), found {_show(sexp)}")])
    head = sexp[0]
    if head == VAL:
        return _parse_val(sexp)
    if head == EXEC:
        return _parse_exec(sexp)
    return decode_instance(sexp)


def unparse(expr: Expression) -> str:
    """Write an expression as text."""
    return dumps(to_sexp(expr))


def to_sexp(expr: Expression) -> list:
    if isinstance(expr, Val):
        attribute = [Symbol(expr.attribute)] if expr.attribute else []
        return [VAL, Symbol(expr.cls), *attribute, *_pairs(expr.key)]
    if isinstance(expr, Exec):
        body = encode_instance(expr.action)[1:]
        return [EXEC, Symbol(expr.cls), Symbol(expr.method), *_pairs(expr.key), *body]
    return encode_instance(expr)


def _pairs(mapping: dict[str, Any]) -> list:
    out: list = []
    for name, value in mapping.items():
        out.append(Keyword(name))
        out.append(encode_value(value))
    return out


# ---- instances --------------------------------------------------------------


def encode_instance(model: Concept) -> list:
    """An ontology model as an S-expression (unset attributes left out)."""
    out: list = [Symbol(class_name(model))]
    for name, info in type(model).model_fields.items():
        value = getattr(model, name)
        if value is None or (isinstance(value, tuple) and not value):
            continue
        out.append(Keyword(info.serialization_alias or info.alias or name))
        out.append(encode_value(value))
    return out


def encode_value(value: Any):
    """A model field's value as an S-expression (what ``unparse`` writes for it)."""
    if isinstance(value, BaseModel):
        return encode_instance(value)
    if isinstance(value, Enum):
        return Symbol(value.value)
    if isinstance(value, bool):
        return _TRUE if value else _FALSE
    if isinstance(value, (tuple, list)):
        return [SEQUENCE, *(encode_value(v) for v in value)]
    return value


def decode_instance(sexp: list, path: str = "") -> Concept:
    """Validate an instance S-expression into its ontology model."""
    problems: list[tuple[str, str]] = []
    model = _decode_instance(sexp, path, problems)
    if problems or model is None:
        raise ExpressionError(problems or [(path, "invalid instance")])
    return model


def _decode_instance(sexp: list, path: str, problems: list) -> Concept | None:
    name = sexp[0]
    cls = CLASSES.get(name) if type(name) is Symbol else None
    where = path or str(name)
    if cls is None:
        problems.append((path, f"unknown class {_show(name)}; known: {', '.join(sorted(CLASSES))}"))
        return None
    attrs = _read_pairs(sexp[1:], where, problems)
    if attrs is None:
        return None
    values = {k: _decode_value(v, f"{where}.{k}", problems) for k, v in attrs.items()}
    try:
        return cls.model_validate(values)
    except ValidationError as exc:
        problems.extend(_validation_problems(exc, where))
        return None


def _read_pairs(items: list, where: str, problems: list) -> dict[str, Any] | None:
    if len(items) % 2:
        problems.append((where, f"expected :attribute value pairs, found an odd number of items ({len(items)})"))
        return None
    out: dict[str, Any] = {}
    ok = True
    for i in range(0, len(items), 2):
        label = items[i]
        if type(label) is not Keyword:
            problems.append((where, f"expected a :keyword, found {_show(label)}"))
            ok = False
            continue
        if label.name in out:
            problems.append((f"{where}.{label.name}", "attribute given twice"))
            ok = False
        out[label.name] = items[i + 1]
    return out if ok else None


def _decode_value(value: Any, path: str, problems: list):
    if type(value) is list:
        if value and type(value[0]) is Symbol:
            if value[0] == SEQUENCE:
                return [_decode_value(v, f"{path}[{i}]", problems) for i, v in enumerate(value[1:])]
            return _decode_instance(value, path, problems)
        return [_decode_value(v, f"{path}[{i}]", problems) for i, v in enumerate(value)]
    if type(value) is Symbol:
        return str(value)  # enums and booleans validate from their names
    if type(value) is Keyword:
        problems.append((path, f"expected a value, found the keyword {value}"))
        return None
    return value


def _validation_problems(exc: ValidationError, where: str) -> list[tuple[str, str]]:
    out = []
    for err in exc.errors(include_url=False):
        loc = ".".join(str(p) for p in err["loc"])
        out.append((f"{where}.{loc}" if loc else where, f"{err['msg']} (found {_show(err.get('input'))})"))
    return out


def _show(value: Any) -> str:
    if isinstance(value, (list, str, int, float)):
        try:
            text = dumps(value)
        except Exception:
            text = repr(value)
    else:
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


# ---- val and exec -----------------------------------------------------------


@cache
def _key_adapter(cls: type[Concept], key: str) -> TypeAdapter:
    for name, info in cls.model_fields.items():
        if key in (name, info.alias, info.serialization_alias):
            return TypeAdapter(Annotated[info.annotation, *info.metadata] if info.metadata else info.annotation)
    raise KeyError(key)


def _canonical(cls: type[Concept], name: str) -> str | None:
    """The language name of an attribute given any accepted spelling, or None."""
    for field_name, info in cls.model_fields.items():
        names = {field_name, info.alias, info.serialization_alias}
        if info.validation_alias is not None and hasattr(info.validation_alias, "choices"):
            names.update(info.validation_alias.choices)
        if name in names:
            return info.serialization_alias or info.alias or field_name
    return None


def _check_class(sexp: list, form: str, problems: list) -> type[Concept] | None:
    needs_name = form == "exec"
    if (
        len(sexp) < (3 if needs_name else 2)
        or type(sexp[1]) is not Symbol
        or (needs_name and type(sexp[2]) is not Symbol)
    ):
        shape = "(exec Class method :key value ...)" if needs_name else "(val Class [attribute] :key value ...)"
        problems.append(("", f"expected {shape}, found {_show(sexp)}"))
        return None
    cls = CLASSES.get(sexp[1])
    if cls is None:
        problems.append(("", f"unknown class {sexp[1]}; known: {', '.join(sorted(CLASSES))}"))
    return cls


def _split_key(cls: type[Concept], attrs: dict, where: str, problems: list) -> tuple[dict, dict]:
    """Separate the primary key from other pairs, canonicalise and type-check it."""
    key: dict[str, Any] = {}
    rest: dict[str, Any] = {}
    given: set[str] = set()
    for name, value in attrs.items():
        canon = _canonical(cls, name)
        if canon in cls.KEY:
            if canon in given:
                problems.append((f"{where}.{name}", f"key {canon} given twice"))
                continue
            given.add(canon)
            try:
                key[canon] = _key_adapter(cls, canon).validate_python(_decode_value(value, where, problems))
            except ValidationError as exc:
                problems.extend(_validation_problems(exc, f"{where}.{canon}"))
        else:
            rest[name] = value
    missing = [k for k in cls.KEY if k not in given]
    if missing:
        problems.append((where, f"missing key {', '.join(':' + k for k in missing)} of {cls.__name__}"))
    return key, rest


def _parse_val(sexp: list) -> Val:
    """``(val Class attribute :key v ...)``; without an attribute it names the whole instance."""
    problems: list[tuple[str, str]] = []
    cls = _check_class(sexp, "val", problems)
    if cls is None:
        raise ExpressionError(problems)
    name = str(sexp[1])
    has_attribute = len(sexp) > 2 and type(sexp[2]) is Symbol
    attribute = str(sexp[2]) if has_attribute else ""
    where = f"{name}.{attribute}" if attribute else name
    canon_attr = ""
    if attribute:
        canon_attr = _canonical(cls, attribute)
        if canon_attr is None:
            problems.append((where, f"{name} has no attribute {attribute}"))
    attrs = _read_pairs(sexp[3 if has_attribute else 2 :], where, problems) or {}
    key, rest = _split_key(cls, attrs, where, problems)
    for extra in rest:
        problems.append((f"{where}.{extra}", f"not part of the key of {name} ({', '.join(cls.KEY) or 'no key'})"))
    if problems:
        raise ExpressionError(problems)
    return Val(cls=name, attribute=canon_attr, key=key)


def _parse_exec(sexp: list) -> Exec:
    problems: list[tuple[str, str]] = []
    cls = _check_class(sexp, "exec", problems)
    if cls is None:
        raise ExpressionError(problems)
    name, method = str(sexp[1]), str(sexp[2])
    where = f"{name}.{method}"
    methods = METHODS.get(name, {})
    model = methods.get(method)
    if model is None:
        known = ", ".join(methods) or "none"
        problems.append((where, f"{name} has no method {method}; known: {known}"))
    attrs = _read_pairs(sexp[3:], where, problems) or {}
    key, rest = _split_key(cls, attrs, where, problems)
    action = None
    if model is not None:
        values = {k: _decode_value(v, f"{where}.{k}", problems) for k, v in rest.items()}
        try:
            action = model.model_validate(values)
        except ValidationError as exc:
            problems.extend(_validation_problems(exc, where))
    if problems or action is None:
        raise ExpressionError(problems or [(where, "invalid arguments")])
    return Exec(cls=name, method=method, key=key, action=action)
