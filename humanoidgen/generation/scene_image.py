"""The picture of an image prompt (`--images`): the head camera's view of a task's scene for a seed, with every
object's annotated key points (dots) and key axes (arrows) drawn and labelled as the API names them
("cube 0 / top", "drawer 0 / handle_out"). Rendered by the parent process from trusted code only (the task's
spec and the seed, as the plan worker's reset builds them), so the same (task, seed) gives the same PNG bytes
on the same renderer."""

from __future__ import annotations

import io
import os

import numpy as np

WIDTH, HEIGHT = 640, 480  # the head camera's colour stream (a D435 at 640x480)
CAMERA = "head"
CAPTION = (
    "The picture: the head camera's view of the scene at the start of the task (the robot looks along +x; "
    "+y, its left, is on the left of the picture). Dots are key points and arrows key axes, labelled "
    "\"<object type> <obj_id> / <name>\" as the API names them (e.g. get_point_in_env(env, name, type, obj_id))."
)

SPEC_CAPTION = (
    "The picture: the head camera's view of the scene your spec builds (its default layout), with the annotated "
    "key points (dots) and key axes (arrows) labelled \"<object type> <obj_id> / <name>\"."
)


def scene_marks(env) -> list:
    """The marks of every annotated object of `env`'s scene: its centre and key points, then its key axes, each
    drawn from the point of the first operation or function that uses it (else from the centre)."""
    from humanoidgen.objects.draw import Mark
    from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env

    marks: list[Mark] = []
    for obj in env.scene.objects:
        ann = obj.annotations
        if ann is None:
            continue
        name = f"{obj.type_name} {obj.obj_id}"
        points = ["center"] + [p.name for p in ann.points if p.name != "center"]
        where = {p: get_point_in_env(env, p, obj.type_name, obj.obj_id) for p in points}
        marks += [Mark(f"{name} / {p}", where[p]) for p in points]
        for axis in ann.axes:
            marks.append(Mark(f"{name} / {axis.name}", where[_axis_origin(ann, axis.name)],
                              get_axis_in_env(env, axis.name, obj.type_name, obj.obj_id)))
    return marks


def _axis_origin(ann, axis: str) -> str:
    for op in ann.operations:
        if axis in (op.approach_axis, op.attach_axis, op.parallel_axis):
            return op.point
    for fn in ann.functions:
        if axis == fn.axis:
            return fn.point
    return "center"


def axis_length(env) -> float:
    """Arrow length (m): about half the largest object, so arrows stand out of small objects without crossing
    the table."""
    sizes = [float(np.max(np.subtract(o.annotations.bbox_max, o.annotations.bbox_min)))
             for o in env.scene.objects if o.annotations is not None]
    return float(np.clip(0.5 * max(sizes, default=0.08), 0.04, 0.10))


def annotated_view(env):
    """The head camera's RGB of `env` now with the scene's marks drawn (a PIL image, WIDTH x HEIGHT)."""
    from PIL import Image

    from humanoidgen.objects.draw import draw_marks
    from humanoidgen.sim.cameras import CameraRig

    with CameraRig(env.model, WIDTH, HEIGHT, shadows=True) as rig:
        frame = rig.render(env.data, CAMERA, depth=False, segmentation=False)
    return draw_marks(Image.fromarray(frame.rgb), scene_marks(env), frame, axis_length(env), labels="beside")


def png_bytes(img) -> bytes:
    """PNG without metadata (no time stamps), so equal pictures are equal bytes."""
    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=False)
    return buf.getvalue()


def scene_png(task, seed: int | None = None) -> bytes:
    """The annotated head-camera view of `task` (a TaskSpec, a task name or a YAML path) for `seed`, as PNG."""
    os.environ.setdefault("MUJOCO_GL", "egl")
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene
    from humanoidgen.tasks.spec import TaskSpec

    spec = task if isinstance(task, TaskSpec) else load_task(task)
    _, env = build_scene(spec, seed)
    return png_bytes(annotated_view(env))
