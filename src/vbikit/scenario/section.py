"""The base of every scenario section (strict pydantic model, its allowed keys) and the scenario
error: shared by the bridge specs (``vbikit.scenario.bridge_spec``) and the rest of the schema."""
from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict

from vbikit.errors import VbikitError


class ScenarioError(VbikitError):
    """An invalid scenario; the message names the offending key(s)."""

    message_names_key = True


class Section(BaseModel):
    """A scenario table: strict types, finite numbers, unknown keys refused."""

    # strict: no coercion ("12" or true are not numbers, 1.5 is not an integer); finite numbers only
    model_config = ConfigDict(extra="forbid", populate_by_name=True, strict=True, allow_inf_nan=False)

    @classmethod
    def allowed_keys(cls, table: dict[str, Any]) -> list[str]:
        """The keys this section accepts (``table``: the section as given)."""
        return [f.alias or n for n, f in cls.model_fields.items()]

    @classmethod
    def key_field(cls, key: str, table: dict[str, Any]) -> Any:
        """The pydantic field (``FieldInfo``) of ``key`` in ``table`` (this section as given), None if
        it has none (its range and unit are then unknown to the error messages)."""
        return next((f for n, f in cls.model_fields.items() if key in (n, f.alias)), None)

    @classmethod
    def missing_note(cls) -> str:
        """What a required table of this section needs, for the error when it is missing (default: its keys)."""
        return "its keys: " + ", ".join(cls.allowed_keys({}))

    @classmethod
    def unknown_key_note(cls, key: str, table: dict[str, Any]) -> str:
        """A hint for the unknown ``key`` of ``table`` ("" for none)."""
        return ""
