"""Sanity bounds and the strict base model shared by the task schema (spec.py) and its targets (targets.py).

Anything beyond these bounds is a typo or a hostile file, and would only fail later, deep in the simulator
(NaN poses) or hang it (an hour-long episode).
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import BaseModel, ConfigDict
from pydantic_core import PydanticCustomError

MAX_POSITION_M = 5.0  # the table is about 0.8 x 1.6 m around the robot
MAX_OFFSET_M = 1.0  # randomization offsets, target offsets
MAX_SIZE_M = 1.0  # tolerances, gaps, heights of success predicates
MAX_YAW_DEG = 360.0
MAX_TIME_LIMIT_S = 3600.0
AXES = "xyz"


class Strict(BaseModel):
    # allow_inf_nan=False: YAML's .nan / .inf are not numbers a layout can use.
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False, defer_build=True)


def bad(message: str, **ctx: Any) -> PydanticCustomError:
    # A custom error reads "field.path: message" in validation_details (no "Value error, " prefix).
    return PydanticCustomError("out_of_range", message, ctx)


def check_number(what: str, v: Any, limit: float, unit: str, positive: bool = False) -> None:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return  # not a number: pydantic's own type check reports it
    if not math.isfinite(v):
        raise bad(f"{what} must be a finite number, got {v}")
    if positive and v <= 0:
        raise bad(f"{what} must be greater than 0, got {v:g} {unit}")
    if abs(v) > limit:
        raise bad(f"{what} = {v:g} {unit} is out of range (at most {limit:g} {unit} in magnitude)")


def check_vector(what: str, v: Any, limit: float) -> Any:
    """Each axis of a position/offset finite and within `limit` metres (before pydantic's tuple parsing, so a
    NaN is reported once, by axis)."""
    if isinstance(v, (list, tuple)):
        for axis, x in zip(AXES, v):
            check_number(f"{what}.{axis}" if what else axis, x, limit, "m")
    return v
