"""Would a stricter end state stop the random baseline? The random baseline (reference plans' action range,
4-action holds, as bench/baselines.py) runs each scene to the time limit without stopping at success; per
action it records the task's verdict, the openness its success judges (the first openness predicate's) and
whether any robot body touches that object. Then it counts the scenes each candidate success rule passes:

- `as is`: the task's predicates at any action (what evaluation does: success ends the episode);
- `released`: the predicates at an action where no robot body touches the object (the paper's "finally,
  the hand releases ...");
- `to the end`: openness within 0.01 of the goal end (0 or 1) at an action, no contact (the paper's "to an
  openness of 0");
- `held 1 s` / `held 5 s`: `released` true for 10 / 50 actions in a row;
- `at the end`: `released` true at the episode's last action (judged at the time limit);
- `by the hand`: the predicates at an action before which no arm link (a robot body that is not a hand's: the
  forearm, the elbow, the shoulder) has touched the object: the paper's "the hand pushes the drawer", not the
  arm swept into it;
- `by the hand, released`: both;
- `end state`: the task's predicates that judge a state (not a process), at any action: for close_drawer, whose
  success also asks the drawer pushed shut by the hand holding its handle (`moved_while_held`), the drawer shut;
- `held over T`: the end state reached while a hand holds the object (thumb against a finger or the palm),
  within one hold that moved it at least T of the way (T = 0.2, 0.3, 0.4): what `moved_while_held` judges.

    python bench/baseline_rules.py --tasks close_drawer,close_box_easy --episodes 20
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))
from provenance import commit  # noqa: E402


def touches(sim, body: str) -> bool:
    """Any robot body (one not in the object's tree, not the table or the world) in contact with the object."""
    m, d = sim.model, sim.data
    root = m.body(body).id
    others = {m.body(o.body).id for o in sim.scene.objects}
    for c in d.contact[: d.ncon]:
        for a, b in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            if m.body_rootid[m.geom_bodyid[b]] != root:
                continue
            mine = m.geom_bodyid[a]
            if m.body_rootid[mine] in others or mine == 0 or m.body(mine).name == "table":
                continue
            return True
    return False


def arm_touches(sim, body: str) -> bool:
    """A robot body that is not part of a hand (fingers, palm) in contact with the object."""
    from humanoidgen.sim.layout import HAND_PREFIX, WRIST_BODY

    m, d = sim.model, sim.data
    root = m.body(body).id
    hand = tuple(p + "_" for p in HAND_PREFIX.values())
    palms = set(WRIST_BODY.values())
    others = {m.body(o.body).id for o in sim.scene.objects}
    for c in d.contact[: d.ncon]:
        for a, b in ((c.geom1, c.geom2), (c.geom2, c.geom1)):
            if m.body_rootid[m.geom_bodyid[b]] != root:
                continue
            mine = m.geom_bodyid[a]
            name = m.body(mine).name
            if m.body_rootid[mine] in others or mine == 0 or name == "table":
                continue
            if not (name.startswith(hand) or name in palms):
                return True
    return False


def judged_part(spec):
    """(object reference, part, goal end) of the task's first openness predicate: what its success moves."""
    for s in spec.success:
        if s.type in ("openness_at_least", "openness_at_most"):
            return s.obj, s.part, 1.0 if s.type == "openness_at_least" else 0.0
    raise ValueError(f"{spec.name} has no openness predicate")


def trace(task: str, episodes: int, action_range) -> list[list[tuple[float, bool, bool, bool, bool, bool]]]:
    """Per scene, per action: (openness of what the success judges, touched, the task's verdict, an arm link
    touched it, the end-state predicates' verdict, a hand holds it)."""
    import torch

    from humanoidgen.envs.config import TaskEnvConfig
    from humanoidgen.envs.task_env import HumanoidTaskEnv
    from humanoidgen.objects.describe import openness
    from humanoidgen.policies.baseline_eval import blind
    from humanoidgen.policies.registry import baseline_policy
    from humanoidgen.policies.rollout import policy_obs
    from humanoidgen.planning.hand_ops import finger_contacts, is_held

    env = HumanoidTaskEnv(task, config=blind(TaskEnvConfig()))
    model = baseline_policy("random", action_range)
    out = []
    try:
        for i in range(episodes):
            obs, _ = env.reset(seed=100_000 + i)
            ref, part, _ = judged_part(env.spec_task)
            obj = env.sim.scene.object(ref.type, ref.id)
            gen = torch.Generator().manual_seed(i)  # evaluation seed 0, episode i: the baselines' draws
            rows: list[tuple[float, bool, bool]] = []
            while len(rows) < env.max_steps:
                for a in model.predict_action(policy_obs(model, [obs], "cpu"), generator=gen)["action"][0].numpy():
                    obs, _, _, _, info = env.step(a)
                    o = openness(env.sim.model, env.sim.data, obj, part)
                    state = all(c["ok"] for c, pr in zip(info["checks"], env.spec_task.success)
                                if not getattr(pr, "history", False))
                    held = any(is_held(finger_contacts(env.sim.model, env.sim.data, s, obj.body))
                               for s in ("left", "right"))
                    rows.append((float(o if o is not None else -1.0), touches(env.sim, obj.body), bool(info["success"]),
                                 arm_touches(env.sim, obj.body), state, held))
                    if len(rows) >= env.max_steps:
                        break
            out.append(rows)
    finally:
        env.close()
    return out


def held_over(rows, goal: float, travel: float) -> bool:
    """The end state reached while held, within one hold that moved the part `travel` or more toward `goal`."""
    start = None
    for o, _, _, _, state, held in rows:
        if not held:
            start = None
            continue
        start = o if start is None else start
        if state and abs(o - start) >= travel and abs(goal - o) <= abs(goal - start):
            return True
    return False


def held_sum(rows, goal: float, travel: float) -> bool:
    """The end state reached while held, the holds together (a hand may let go and grip again) having moved the
    part `travel` or more toward `goal` (movement counted between two held actions in a row)."""
    moved, last = 0.0, None
    for o, _, _, _, state, held in rows:
        if not held:
            last = None
            continue
        if last is not None:
            moved += max(0.0, abs(goal - last) - abs(goal - o))
        last = o
        if state and moved >= travel:
            return True
    return False


def rules(rows: list[tuple[float, bool, bool, bool, bool, bool]], goal: float) -> dict[str, bool]:
    released = [ok and not touched for _, touched, ok, *_ in rows]
    armed, by_hand = False, []
    for _, _, ok, arm, *_ in rows:
        armed = armed or arm
        by_hand.append(ok and not armed)

    def run_of(k: int) -> bool:
        n = 0
        for r in released:
            n = n + 1 if r else 0
            if n >= k:
                return True
        return False

    return {"as is": any(ok for _, _, ok, *_ in rows), "released": any(released),
            "end state": any(r[4] for r in rows),
            **{f"held over {tr}": held_over(rows, goal, tr) for tr in (0.2, 0.3, 0.4)},
            **{f"holds over {tr}": held_sum(rows, goal, tr) for tr in (0.3, 0.4)},
            "to the end": any(r and abs(o - goal) <= 0.01 for r, (o, *_) in zip(released, rows)),
            "held 1 s": run_of(10), "held 5 s": run_of(50), "at the end": released[-1],
            "by the hand": any(by_hand), "by the hand, released": any(h and r for h, r in zip(by_hand, released))}


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tasks", help="comma list (default: the tasks bench/results/baselines.json has above 10%%)")
    p.add_argument("--episodes", type=int, default=20)
    p.add_argument("--ranges", type=Path, default=Path("data/baselines/ranges.json"),
                   help="bench/baselines.py's cache of the reference plans' action ranges")
    p.add_argument("--out", type=Path, default=ROOT / "results" / "baseline_rules.json")
    args = p.parse_args()

    from baselines import plan_range

    from humanoidgen.policies.baselines import ActionRange
    from humanoidgen.tasks.registry import load_task

    result, t0 = {}, time.perf_counter()
    if args.tasks:
        tasks = [t.strip() for t in args.tasks.split(",")]
    else:
        rows = json.loads((ROOT / "results" / "baselines.json").read_text())["rows"]
        tasks = sorted({r["task"] for r in rows if r["success_mean"] > 0.10})
    for task in tasks:
        r = plan_range(task, 5, args.ranges)
        goal = judged_part(load_task(task))[2]
        per_scene = [rules(rows, goal) for rows in trace(task, args.episodes, ActionRange.of(r["low"], r["high"], "plans"))]
        result[task] = {k: sum(s[k] for s in per_scene) for k in per_scene[0]}
        print(task, result[task], flush=True)
    args.out.write_text(json.dumps({"settings": {"episodes": args.episodes, "seeds": [0], "commit": commit(),
                                                 "cpu_count": os.cpu_count(),
                                                 "minutes": round((time.perf_counter() - t0) / 60, 1)},
                                    "scenes_passed": result}, indent=1))
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
