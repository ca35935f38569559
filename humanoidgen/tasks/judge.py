"""A task's success predicates evaluated on a simulation, each as {"predicate", "ok", "detail"}.

Which simulation is judged decides whether the verdict can be trusted: episodes are judged on their replay
(`episodes.replay`), never on the plan worker's own state; the gym environments judge their own simulation.
A predicate over the episode's course (`moved_while_held`) needs a `Watch` that saw every control step; judged
without one it does not hold.
"""

from __future__ import annotations


def judge(spec, env, watch=None) -> list[dict]:
    """Every success predicate of `spec` on `env` (a HumanoidEnv): all must hold for the task to be done.
    `watch` (tasks.watch.Watch): what the episode's predicates over time have seen."""
    out = []
    for k, pred in enumerate(spec.success):
        if getattr(pred, "history", False):
            r = pred.evaluate(env, watch.memory[k] if watch is not None else None)
        else:
            r = pred.evaluate(env)
        out.append({"predicate": pred.type, "ok": bool(r.ok), "detail": r.detail})
    return out
