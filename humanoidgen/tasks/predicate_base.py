"""What every success predicate shares: object references ("cube[0]" or {type: cube, id: 0}), the verdict with
its detail, and reading an object off the simulation."""

from __future__ import annotations

import re
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field

from humanoidgen.sim.scene import SceneObject

_REF = re.compile(r"^\s*([a-z_]+)\s*\[\s*(\d+)\s*\]\s*$")


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, defer_build=True)


class ObjRef(_Strict):
    type: str
    id: int = Field(default=0, ge=0)

    def __str__(self) -> str:
        return f"{self.type}[{self.id}]"


def _parse_ref(v: Any) -> Any:
    if isinstance(v, str):
        m = _REF.match(v)
        if not m:
            raise ValueError(f"object reference must look like 'cube[0]', got {v!r}")
        return {"type": m.group(1), "id": int(m.group(2))}
    return v


Ref = Annotated[ObjRef, BeforeValidator(_parse_ref)]


class PredicateResult(_Strict):
    ok: bool
    detail: str


def _cm(x: float) -> str:
    return f"{x * 100:.1f} cm"


def _obj(env, ref: ObjRef) -> SceneObject:
    return env.scene.object(ref.type, ref.id)


def _name(ref: ObjRef) -> str:
    return f"{ref.type} {ref.id}"


def _part_name(ref: ObjRef, part: str | None) -> str:
    """The object, or its part with a joint of its own ("safe 0's knob")."""
    return _name(ref) if part is None else f"{_name(ref)}'s {part}"


