"""The schema of the family data files (humanoidgen/objects/families/): a family's `family.yaml` and its models.

A model file is one model (`type_id`) of a family: its description and parameters (dimensions in metres,
colours as RGBA in [0, 1], masses in kg, materials, joint dynamics). `family.yaml` holds what the family's
models share: `defaults` (parameters a model file may leave out or override) and the family's annotation
vocabulary: points (with the moving part they are on, if any) and axes, each with a description in words (plan
authors read these), operations, functions, and for articulated families what their openness moves. Point
positions are not data: the family code derives them from the parameters, so that they
follow the geometry. Every model is validated against its family's parameter model below (unknown fields are
errors, numbers must be numbers).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import Field, model_validator

from humanoidgen.objects.schema import KeyAxis, Operation, _Strict

# Numbers are strict: a quoted "0.04" in a file is an error, not silently a float.
Num = Annotated[float, Field(strict=True)]
Pos = Annotated[float, Field(strict=True, gt=0.0)]
NonNeg = Annotated[float, Field(strict=True, ge=0.0)]
Unit = Annotated[float, Field(strict=True, ge=0.0, le=1.0)]
Count = Annotated[int, Field(strict=True, ge=3)]
Vec3 = tuple[Num, Num, Num]
Size3 = tuple[Pos, Pos, Pos]
RGBA = tuple[Unit, Unit, Unit, Unit]


# -- family.yaml ------------------------------------------------------------------------------------------------
class PointSpec(_Strict):
    """An annotated point of a family; its position comes from the family code. The description says where it is
    in words (plan authors read it: the prompts and the docs show it), with its direction from the object's
    middle where that matters ("on the side facing the robot")."""

    name: str = Field(min_length=1)
    part: str | None = None  # articulated families: the moving part it is on (it moves with it)
    description: str = Field(min_length=1)


class AxisSpec(KeyAxis):
    """An annotated axis of a family: its direction in the object's frame (or its part's, with the part closed)
    and, required here, what that direction is in words, as the robot sees the object at yaw 0."""

    description: str = Field(min_length=1)


class OpennessSpec(_Strict):
    """What an articulated family's openness means for one of its joints (the object's own, or a part's that has
    a joint of its own), for plan authors: which part moves and which way, in which physical unit the models'
    ranges are shown, and how far plans should ask for (a limit measured, not a joint limit)."""

    part: str  # the part it moves; the object's own openness is the one whose part has no joint of its own
    unit: Literal["deg", "mm"]  # deg for a hinge, mm for a slide
    moves: str = Field(min_length=1)  # what moves which way as openness grows from 0 (closed) to 1 (open)
    recommended_max: Unit | None = None  # ask for at most this openness (why: `note`)
    note: str = ""


class OperationSpec(_Strict):
    operation: Operation
    point: str
    approach_axis: str
    attach_axis: str
    parallel_axis: str
    # A grasp around a round body: its width is the body's diameter at the point, computed from the geometry.
    wrap: bool = False
    # Only for models whose geometry has this point (a long block's second end); others leave it out.
    requires: str | None = None


class FunctionSpec(_Strict):
    function: str
    point: str
    axis: str
    requires: str | None = None


class UsableRule(_Strict):
    """What an imported model must offer for the family's tasks to use it (objects/imported/usable.py): its point
    at least `min_height` above its base, or standing at least `min_out` out of `from_point` toward the robot
    (-x), closed. `why` says what fails otherwise; a model that fails is not drawn by --randomize-models."""

    point: str
    min_height: float | None = Field(default=None, gt=0.0, le=2.0)
    min_out: float | None = Field(default=None, gt=0.0, le=1.0)
    from_point: str | None = None
    why: str = Field(min_length=1)

    @model_validator(mode="after")
    def _one_measure(self) -> UsableRule:
        if (self.min_height is None) == (self.min_out is None):
            raise ValueError("give one of min_height and min_out")
        if (self.min_out is None) != (self.from_point is None):
            raise ValueError("min_out needs from_point (and only min_out takes it)")
        return self


class FamilyFile(_Strict):
    """A family's `family.yaml`."""

    family: str = Field(min_length=1)
    articulated: bool
    # Fixed to the table (no free joint), like an articulated object's root: a barrier the hands work around.
    static: bool = False
    defaults: dict[str, Any] = Field(default_factory=dict)
    points: list[PointSpec] = Field(default_factory=list)
    axes: list[AxisSpec]
    operations: list[OperationSpec]
    functions: list[FunctionSpec] = Field(default_factory=list)
    openness: list[OpennessSpec] = Field(default_factory=list)  # articulated families: one per joint
    usable: list[UsableRule] = Field(default_factory=list)

    @model_validator(mode="after")
    def _openness_for_articulated(self) -> "FamilyFile":
        if self.articulated != bool(self.openness):
            raise ValueError("an articulated family says what its openness moves (openness: [...]); "
                             "only articulated families have one")
        return self


# -- model files --------------------------------------------------------------------------------------------------
class ModelFile(_Strict):
    """What every model file has; each family's parameter model adds its own fields."""

    type_id: Annotated[int, Field(strict=True, ge=0)]
    description: str = Field(min_length=1)


class RigidParams(ModelFile):
    rgba: RGBA
    mass: Pos
    material: str  # a name in families/materials.yaml (sliding, torsional, rolling friction)


class CubeParams(RigidParams):
    size: Size3  # full edge lengths x, y, z


class BarrierParams(RigidParams):
    size: Size3  # full extents x, y, z of the box (a static family: its mass is never simulated)


class BottleParams(RigidParams):
    radius: Pos
    body_height: Pos
    neck_radius: Pos
    neck_height: Pos
    cap_rgba: RGBA


class CanParams(RigidParams):
    radius: Pos
    height: Pos


class PlateParams(RigidParams):
    radius: Pos
    thickness: Pos
    rim_height: NonNeg  # 0: a flat board


class _Container(RigidParams):
    radius: Pos
    height: Pos
    wall: Pos
    bottom: Pos
    n_walls: Count
    handle_reach: Pos
    handle_thick: Pos


class CupParams(_Container):
    handle_style: Literal["loop"]


class PotParams(_Container):
    # "bar": a flat horizontal tab on each side, handle_width wide; "post": an upright round grip on each side
    # (handle_thick across, handle_height tall, its axis handle_reach off the wall), held to the wall by an arm
    # at each end: a grip for a hand that wraps it (both hands lifting the pot).
    handle_style: Literal["bar", "post"]
    handle_width: Pos | None = None
    handle_height: Pos | None = None
    handle_rgba: RGBA

    @model_validator(mode="after")
    def _style_sizes(self) -> "PotParams":
        need = {"bar": "handle_width", "post": "handle_height"}[self.handle_style]
        if getattr(self, need) is None:
            raise ValueError(f"handle_style {self.handle_style} needs {need}")
        return self


class BowlParams(RigidParams):
    bottom_radius: Pos
    wall_length: Pos
    tilt_deg: Annotated[float, Field(strict=True, ge=0.0, lt=90.0)]
    wall: Pos
    bottom: Pos
    n_walls: Count


class JointDynamics(_Strict):
    damping: NonNeg
    frictionloss: NonNeg
    armature: NonNeg = 0.005


class ArticulatedParams(ModelFile):
    rgba: RGBA
    # Mass of each box geom (kg) by its name without the object prefix; the build checks that every geom has one.
    masses: dict[str, Pos]
    # The main part stays where a hand leaves it only from this openness up (below, it falls shut by its own
    # weight); None: anywhere. Measured; the prompts show it.
    holds_from: Unit | None = None


class DrawerParams(ArticulatedParams):
    depth: Pos
    width: Pos
    height: Pos
    travel: Pos
    drawer_rgba: RGBA
    handle_rgba: RGBA
    shell_wall: Pos
    clearance: Pos
    drawer_wall: Pos
    handle_offset: Pos  # the bar's centre in front of the drawer's front face
    handle_drop: Pos  # the bar's centre below the drawer's top
    handle_bar_half: Size3  # half sizes of the bar (x, y, z)
    handle_post_half: Size3
    handle_post_y: Pos  # the two posts at +-this from the middle
    slide: JointDynamics


class LaptopParams(ArticulatedParams):
    depth: Pos
    width: Pos
    base_h: Pos
    screen_t: Pos
    open_deg: Pos
    screen_rgba: RGBA
    grip_depth: Pos  # a grasp over the screen's top edge centres this far in from the edge
    hinge: JointDynamics


class BoxParams(ArticulatedParams):
    depth: Pos
    width: Pos
    height: Pos
    open_deg: Pos
    lid_rgba: RGBA
    wall: Pos
    lid_thick: Pos
    tab_half: Pos  # half length of the tab on the lid's front edge
    grip_under: NonNeg  # a grasp of the tab centres this far under its tip (toward the lid's inner side)
    pinch_in: Pos  # a pinch of the tab centres this far in from its tip (toward the hinge)
    hinge: JointDynamics


class SafeParams(ArticulatedParams):
    """objects/safe.py: a shell open toward the robot, a door on a vertical hinge at its right (as the robot sees
    it) with a vertical handle bar on two posts, and a knob with a fin on the door, on a hinge of its own."""

    depth: Pos
    width: Pos
    height: Pos
    wall: Pos  # the shell's
    door_thick: Pos
    door_gap: tuple[Pos, Pos]  # the door is this much narrower (y) and shorter (z) than half the opening, per side
    door_rgba: RGBA
    door_open_deg: Pos
    handle_offset: Pos  # the bar's axis off the door's outer face
    handle_in: Pos  # the bar's axis in from the door's free edge
    handle_z: Num  # the bar's middle above the door's middle
    handle_half_len: Pos
    handle_radius: Pos
    handle_post_half: tuple[Pos, Pos]  # the posts' half sizes across (y, z); their length spans door to bar
    handle_post_at: Unit  # the posts at +-this share of the bar's half length from its middle
    metal_rgba: RGBA  # handle and knob
    knob_in: Pos  # the knob's axis in from the door's free edge
    knob_z: Num  # the knob's axis above the door's middle
    knob_base_half: Size3  # on the door (x: out of it)
    knob_fin_half: Size3  # across the base: along the knob's axis, across it, its thickness
    knob_open_deg: Pos
    door_edge_in: Pos  # the door_edge point in from the free edge
    door_inner_in: Pos  # the door_inner point in from the free edge
    hinge: JointDynamics
    knob_hinge: JointDynamics


class ToasterParams(ArticulatedParams):
    depth: Pos
    width: Pos
    height: Pos
    travel: Pos
    lever_half: Size3  # half sizes of the lever (x: how far it sticks out of the front face)
    lever_rgba: RGBA
    slot_rgba: RGBA
    slide: JointDynamics
