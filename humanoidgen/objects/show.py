"""Pictures of annotated assets: the object rendered with its key points (dots) and key axes (arrows, drawn
from the point of the operation or function that uses them), labelled. Articulated objects are shown at two
openness values; hands show their grasp, pinch and press annotations."""

from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw

from humanoidgen.objects.draw import Mark, draw_marks

from humanoidgen.objects.library import add_object
from humanoidgen.objects.articulated import set_openness
from humanoidgen.objects.hands import hand_axes, hand_points
from humanoidgen.objects.queries import get_axis_in_env, get_point_in_env
from humanoidgen.sim.cameras import CameraRig
from humanoidgen.sim.env import HumanoidEnv
from humanoidgen.sim.geometry import look_at_quat
from humanoidgen.sim.layout import Side
from humanoidgen.sim.scene import SceneBuilder

INSPECT_CAM = "inspect"


def _object_items(env: HumanoidEnv, type_name: str, openness: float | None) -> list:
    ann = env.scene.object(type_name, 0).annotations
    items = [Mark("center", get_point_in_env(env, "center", type_name, 0, openness=openness))]
    for op in ann.operations:
        p = get_point_in_env(env, op.point, type_name, 0, openness=openness)
        items.append(Mark(f"{op.operation}: {op.point} (approach)", p,
                      get_axis_in_env(env, op.approach_axis, type_name, 0, openness=openness)))
    for fn in ann.functions:
        p = get_point_in_env(env, fn.point, type_name, 0, openness=openness)
        items.append(Mark(f"{fn.function}: {fn.point} / {fn.axis}", p,
                      get_axis_in_env(env, fn.axis, type_name, 0, openness=openness)))
    return items


def _render(builder: SceneBuilder, eye: np.ndarray, target: np.ndarray, width: int, height: int,
            setup=None, hide_robot: bool = False) -> tuple[HumanoidEnv, object, CameraRig]:
    builder.spec.worldbody.add_camera(name=INSPECT_CAM, pos=eye, quat=look_at_quat(eye, target), fovy=45.0)
    env = HumanoidEnv(builder.build())
    if setup is not None:
        setup(env)
    rig = CameraRig(env.model, width, height, shadows=True, hide_robot=hide_robot)
    return env, rig.render(env.data, INSPECT_CAM, depth=False, segmentation=False), rig


def show_object(type_name: str, type_id: int = 0, width: int = 640, height: int = 480) -> Image.Image:
    """The object alone on the table with its annotations; articulated ones at openness 0.3 and 1."""
    from humanoidgen.objects import library

    ann = library.annotations(type_name, type_id)
    return _show(type_name, type_id, ann, lambda b: add_object(b, type_name, type_id, pos=(-0.25, 0.0)), width,
                 height)


def show_imported(model, width: int = 640, height: int = 480) -> Image.Image:
    """An imported model (objects.imported.model_file.ImportedModel) from its folder, before it is in a search
    path: the picture an import writes beside the model."""
    from humanoidgen.objects.imported.build import build_imported
    from humanoidgen.sim.geometry import yaw_quat
    from humanoidgen.sim.layout import TABLE_TOP_Z

    ann, fam = model.annotations, model.info.family

    def add(builder: SceneBuilder):
        pos = np.array([-0.25, 0.0, TABLE_TOP_Z - ann.bbox_min[2]])
        obj, body = builder.add_object_body(fam, pos, yaw_quat(0.0), type_id=model.info.type_id,
                                            free=ann.articulation is None, annotations=ann)
        build_imported(builder.spec, body, model)
        return obj

    return _show(fam, model.info.type_id, ann, add, width, height)


def _show(type_name: str, type_id: int, ann, add, width: int, height: int) -> Image.Image:
    size = float(np.max(np.subtract(ann.bbox_max, ann.bbox_min)))
    builder = SceneBuilder(msaa_samples=4)
    obj = add(builder)
    center = np.array([-0.25, 0.0, -ann.bbox_min[2]])
    eye = center + np.array([-1.6, 0.9, 1.3]) * max(size, 0.08) * 1.6
    panels = []
    openings = [0.3, 1.0] if ann.articulation is not None else [None]
    env, _, rig = _render(builder, eye, center, width, height, hide_robot=True)
    with rig:
        for o in openings:
            if o is not None:
                set_openness(env.model, env.data, obj.body, obj.annotations, o)
            frame = rig.render(env.data, INSPECT_CAM, depth=False, segmentation=False)
            img = draw_marks(Image.fromarray(frame.rgb), _object_items(env, type_name, o), frame,
                             axis_len=0.4 * max(size, 0.08))
            title = f"{type_name} type_id={type_id}" + ("" if o is None else f" openness={o}")
            ImageDraw.Draw(img).text((4, height - 14), title, fill=(0, 0, 0))
            panels.append(img)
    out = Image.new("RGB", (width * len(panels), height))
    for i, p in enumerate(panels):
        out.paste(p, (i * width, 0))
    return out


def show_hand(side: Side, width: int = 640, height: int = 480) -> Image.Image:
    """One hand, close up from above and to the side, with its points and axes."""
    from humanoidgen.sim.layout import WRIST_BODY

    builder = SceneBuilder(msaa_samples=4)
    # Build once to learn where the hand is at the initial posture, then aim the inspection camera at it.
    probe = HumanoidEnv(SceneBuilder().build())
    pos, R = probe.data.xpos[probe.model.body(WRIST_BODY[side]).id], probe.data.xmat[
        probe.model.body(WRIST_BODY[side]).id].reshape(3, 3)
    target = pos + R @ np.array([0.15, 0.0, 0.0])
    eye = target + np.array([-0.05, 0.25 if side == "left" else -0.25, 0.30])
    env, frame, rig = _render(builder, eye, target, width, height)
    rig.close()
    pts, axes = hand_points(side), hand_axes(side)
    items = [Mark(name, get_point_in_env(env, name)) for name in pts]
    base = get_point_in_env(env, f"palm_center_{side}_hand")
    items += [Mark(name, base, get_axis_in_env(env, name)) for name in axes]
    return draw_marks(Image.fromarray(frame.rgb), items, frame, axis_len=0.08)
