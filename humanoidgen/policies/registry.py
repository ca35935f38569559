"""The policies by name: the trained ones (their config class, model class and what each needs from the data
and the env) and the baselines that need no training (`baselines/`), which evaluation runs beside them."""

from __future__ import annotations

from dataclasses import dataclass

from humanoidgen.policies.config import PolicyConfig


@dataclass(frozen=True)
class PolicyType:
    name: str
    config_cls: type[PolicyConfig]
    needs: str  # what a zarr must hold besides state and action, as a reason for an error message

    def model_cls(self):
        if self.name == "dp":
            from humanoidgen.policies.dp.model import DPPolicy

            return DPPolicy
        from humanoidgen.policies.dp3.model import DP3Policy

        return DP3Policy

    def config(self, overrides: dict | None = None) -> PolicyConfig:
        """The default config with `overrides` (nested dicts: {"unet": {"down_dims": [64, 128, 256]}})."""
        base = self.config_cls().model_dump()
        return self.config_cls.model_validate(_merge(base, overrides or {}))


def _merge(base: dict, over: dict) -> dict:
    out = dict(base)
    for k, v in over.items():
        out[k] = _merge(base[k], v) if isinstance(v, dict) and isinstance(base.get(k), dict) else v
    return out


def _types() -> dict[str, PolicyType]:
    from humanoidgen.policies.dp.config import DPConfig
    from humanoidgen.policies.dp3.config import DP3Config

    return {"dp": PolicyType("dp", DPConfig, "DP needs the camera images"),
            "dp3": PolicyType("dp3", DP3Config, "DP3 needs point clouds")}


POLICY_NAMES = ("dp", "dp3")
BASELINE_NAMES = ("random", "noop")


def policy_type(name: str) -> PolicyType:
    types = _types()
    if name in BASELINE_NAMES:
        raise ValueError(f"{name} is a baseline and needs no training; evaluate it with: hgen policy eval "
                         f"--policy {name} TASK")
    if name not in types:
        raise ValueError(f"unknown policy {name!r}; policies: {', '.join(POLICY_NAMES)}; baselines: "
                         f"{', '.join(BASELINE_NAMES)}")
    return types[name]


def baseline_policy(name: str, action_range=None, hold: int | None = None):
    """A baseline by name: `random` draws its targets in `action_range` (an `ActionRange`; required) and holds
    each for `hold` actions (default `RANDOM_HOLD_ACTIONS`); `noop` holds the start posture."""
    from humanoidgen.policies.baselines import RANDOM_HOLD_ACTIONS

    if name == "random":
        from humanoidgen.policies.baselines.random_policy import RandomPolicy

        if action_range is None:
            raise ValueError("the random baseline needs an action range")
        return RandomPolicy(action_range, hold or RANDOM_HOLD_ACTIONS)
    if name == "noop":
        from humanoidgen.policies.baselines.noop_policy import NoopPolicy

        return NoopPolicy()
    raise ValueError(f"unknown baseline {name!r}; baselines: {', '.join(BASELINE_NAMES)}")
