"""Visual randomization changes pixels, not physics, and re-renders exactly from the stored parameters."""

from __future__ import annotations

import json
import os

import mujoco
import numpy as np

os.environ.setdefault("MUJOCO_GL", "egl")

from humanoidgen.scenes.dressing import SceneDressing, episode_dressing  # noqa: E402
from humanoidgen.scenes.visuals import CAMERA_JITTER, DISTRACTOR_ABS_Y, VisualParams, draw_visuals  # noqa: E402
from humanoidgen.sim.layout import OPERABLE_RANGE  # noqa: E402

TASK = "blocks_stack_easy"


def _trajectory(dressing: SceneDressing | None, steps: int = 40) -> tuple[np.ndarray, object]:
    """Objects' poses while the arms sweep and the first block is thrown at the second from above."""
    from humanoidgen.tasks.registry import load_task
    from humanoidgen.tasks.scene import build_scene

    scene, env = build_scene(load_task(TASK), seed=1, settle_s=0.1, dressing=dressing)
    a = env.init_action()
    m, d = env.model, env.data
    first, second = (m.body(o.body) for o in scene.objects[:2])
    adr, vadr = m.jnt_qposadr[first.jntadr[0]], m.jnt_dofadr[first.jntadr[0]]
    d.qpos[adr + 2] += 0.08
    toward = d.xpos[second.id] - d.xpos[first.id]
    d.qvel[vadr:vadr + 2] = 1.5 * toward[:2] / np.linalg.norm(toward[:2])
    mujoco.mj_forward(m, d)
    out = []
    for i in range(steps):
        b = a.copy()
        b[:14] += 0.4 * np.sin(np.linspace(0, 3, 14) + 0.1 * i)  # arms sweep; some contacts happen
        env.step(b)
        out.append(np.concatenate([np.concatenate(env.object_pose(o.body)) for o in scene.objects]))
    return np.array(out), env


def _render(env, camera: str = "front") -> np.ndarray:
    from humanoidgen.sim.cameras import CameraRig

    with CameraRig(env.model, 160, 120) as rig:
        return rig.render(env.data, camera, depth=False, segmentation=False).rgb


def test_draws_are_reproducible_bounded_and_outside_the_workspace():
    a, b = draw_visuals(4), draw_visuals(4)
    assert a == b and a != draw_visuals(5)
    assert VisualParams.from_dict(json.loads(json.dumps(a.to_dict()))) == a
    for seed in range(40):
        v = draw_visuals(seed)
        for name, j in v.cameras.items():
            de, dt, df = CAMERA_JITTER[name]
            assert np.all(np.abs(j.eye) <= de) and np.all(np.abs(j.target) <= dt) and abs(j.fovy) <= df
        for d in v.distractors:
            assert abs(d.pos[1]) >= DISTRACTOR_ABS_Y[0] > max(abs(r.y[0]) for r in OPERABLE_RANGE.values())


def test_changes_pixels_not_physics_and_rerenders_from_metadata():
    stored = episode_dressing(None, True, 3)
    dressing = SceneDressing.from_dict(json.loads(json.dumps(stored)))  # as read back from an episode record
    plain, env_plain = _trajectory(None)
    dressed, env_dressed = _trajectory(dressing)
    assert np.abs(plain[-1] - plain[0]).max() > 1e-4  # the sweep did move something...
    np.testing.assert_array_equal(plain, dressed)  # ...identically with and without randomization
    m = env_dressed.model
    extra = [g for g in range(m.ngeom) if (m.geom(g).name or "").startswith("distractor_")]
    assert all(m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0 for g in extra)
    img_plain, img_dressed = _render(env_plain), _render(env_dressed)
    assert np.mean(np.any(img_plain != img_dressed, axis=-1)) > 0.2
    # The same stored parameters build the same look: the same pixels at the same configuration.
    again = SceneDressing.from_dict(stored)
    _, env_again = _trajectory(again, steps=1)
    env_again.data.qpos[:] = env_dressed.data.qpos
    mujoco.mj_forward(env_again.model, env_again.data)
    mujoco.mj_forward(env_dressed.model, env_dressed.data)
    np.testing.assert_array_equal(_render(env_again), _render(env_dressed))


def test_episode_dressing_records_room_and_look():
    assert episode_dressing(None, False, 3) is None
    d = episode_dressing("random", True, 3)
    assert d["room"]["seed"] == SceneDressing.from_dict(d).room.seed and d["visuals"]["seed"] == 3
    assert d["o_to_o_prime"] is not None
    assert episode_dressing("random", False, 3) == episode_dressing("random", False, 3)
    assert episode_dressing("random", False, 3)["room"] != episode_dressing("random", False, 4)["room"]
