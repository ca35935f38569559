"""A task's success predicates evaluated on a simulation, each as {"predicate", "ok", "detail"}.

Which simulation is judged decides whether the verdict can be trusted: episodes are judged on their replay
(`episodes.replay`), never on the plan worker's own state; the gym environments judge their own simulation.
"""

from __future__ import annotations


def judge(spec, env) -> list[dict]:
    """Every success predicate of `spec` on `env` (a HumanoidEnv): all must hold for the task to be done."""
    out = []
    for pred in spec.success:
        r = pred.evaluate(env)
        out.append({"predicate": pred.type, "ok": bool(r.ok), "detail": r.detail})
    return out
