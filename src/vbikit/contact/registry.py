"""The tire models by scenario name: registration, construction from parameters, the catalogue.

A tire model is a [`TireModel`][vbikit.contact.TireModel] subclass that declares its scenario
``name``, a one-line ``description``, its ``references`` (keys of ``vbikit.references.REFERENCES``)
and its ``Parameters`` (a [`TireParameters`][vbikit.contact.TireParameters] pydantic model: the keys of
its ``[tire]`` table besides ``model``, with their ranges, defaults and units).  Decorating the
class with [`register_tire`][vbikit.contact.register_tire] makes it selectable by name everywhere: scenario files, studies,
the field workflow, ``vbikit cite`` and ``vbikit presets``.
"""
from __future__ import annotations

import re
import typing
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

from pydantic import ValidationError

from vbikit.references import REFERENCES

if TYPE_CHECKING:
    from vbikit.contact.base import TireModel, TireParameters

T = TypeVar("T", bound="type[TireModel]")

#: every registered tire model class by its scenario name, in registration order
TIRE_MODELS: dict[str, type[TireModel]] = {}


def register_tire(cls: T) -> T:
    """Register tire model class ``cls`` under ``cls.name`` (usable as a class decorator).

    Registering a class again under the same name (a module executed twice) replaces the
    earlier definition.

    Parameters
    ----------
    cls : type of TireModel
        The tire model class; its ``name`` is the scenario's ``[tire] model``.

    Returns
    -------
    type of TireModel
        ``cls`` itself.

    Raises
    ------
    ValueError
        An empty name, a name taken by another class, or a reference key that is not in
        ``vbikit.references.REFERENCES``.
    """
    name = getattr(cls, "name", "")
    if not name:
        raise ValueError(f"tire model {cls.__qualname__} has no scenario name (class attribute `name`)")
    old = TIRE_MODELS.get(name)
    if old is not None and (old.__module__, old.__qualname__) != (cls.__module__, cls.__qualname__):
        raise ValueError(f"tire model name {name!r} is taken by {old.__module__}.{old.__qualname__}")
    unknown = [k for k in cls.references if k not in REFERENCES]
    if unknown:
        raise ValueError(f"tire model {name!r}: unknown reference key(s) {', '.join(map(repr, unknown))} "
                         "(keys of vbikit.references.REFERENCES)")
    TIRE_MODELS[name] = cls
    return cls


def tire_model(name: str) -> type[TireModel]:
    """The tire model class registered as ``name``; ValueError listing the allowed names otherwise."""
    try:
        return TIRE_MODELS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown tire model {name!r}; allowed: {', '.join(TIRE_MODELS)}") from None


def tire_parameters(name: str, parameters: Mapping[str, Any], common: Sequence[str] = ()) -> TireParameters:
    """``parameters`` validated by the ``Parameters`` model of tire model ``name`` (defaults filled in).

    Raises ValueError naming an unknown key and listing the allowed ones (``common``, keys the
    caller accepts besides the model's, first), or the pydantic ValidationError (a ValueError)
    of a value out of range, located at the key.
    """
    cls = tire_model(name)
    allowed = [*common, *cls.Parameters.model_fields]
    for key in parameters:
        if key not in allowed:
            head = f"{key}: unknown key" if re.fullmatch(r"[a-z_]+", str(key)) else f"unknown key {key!r}"
            hint = f"allowed keys: {', '.join(allowed)}" if allowed else "it takes no parameters"
            raise ValueError(f"{head} for tire model {name!r}; {hint}")
    return cls.Parameters.model_validate(dict(parameters))


def tire_from_parameters(name: str, **parameters: Any) -> TireModel:
    """The tire model ``name`` built from its scenario parameters (e.g. ``n_points=4`` for
    ``"multipoint"``); the defaults of its ``Parameters`` for the others.  Raises ValueError
    naming the model and the offending key."""
    try:
        validated = tire_parameters(name, parameters)
    except ValidationError as err:
        from vbikit._validation import bound_message, key_name

        fields = tire_model(name).Parameters.model_fields

        def problem(e: Any) -> str:
            text = bound_message(e, fields.get(e["loc"][-1])) or f"{e['msg']} (got {e['input']!r})"
            return f"{key_name(tuple(e['loc']))}: {text}"

        problems = "; ".join(problem(e) for e in err.errors())
        raise ValueError(f"tire model {name!r}: {problems}") from None
    return tire_model(name).from_parameters(validated)


def _unit(description: str) -> str:
    m = re.search(r"\[([^\[\]]+)\]\s*$", description)
    return "" if m is None or m.group(1) == "-" else m.group(1)


def parameter_summary(parameters: type[TireParameters]) -> str:
    """The keys of a ``Parameters`` model with defaults and units: ``"n_points (default 6),
    contact_length (default 0.254 m), layout = ends | cells (default ends)"``."""
    parts = []
    for key, field in parameters.model_fields.items():
        unit = _unit(field.description or "")
        default = field.default
        shown = f"{default:g}" if isinstance(default, float) else str(default).lower() if isinstance(default, bool) \
            else str(default)
        choices = typing.get_args(field.annotation) if typing.get_origin(field.annotation) is typing.Literal else ()
        name = f"{key} = {' | '.join(map(str, choices))}" if choices else key
        parts.append(f"{name} (default {shown}{' ' + unit if unit else ''})")
    return ", ".join(parts)


def tire_catalogue() -> list[tuple[str, str]]:
    """``(name, one-line description with the parameters and their defaults)`` of every
    registered tire model, in registration order (what ``vbikit presets`` lists)."""
    out = []
    for name, cls in TIRE_MODELS.items():
        params = parameter_summary(cls.Parameters)
        out.append((name, cls.description + (f"; {params}" if params else "")))
    return out
