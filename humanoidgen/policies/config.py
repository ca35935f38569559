"""Settings shared by the diffusion policies: the action sequence they denoise, the U-Net, the noise schedule
and the training recipe. Defaults follow the DP / DP3 code the paper trains with (RoboTwin's robot_dp3.yaml:
horizon 8, 3 observation steps, 100 DDPM steps with the squared-cosine schedule, 10 DDIM steps at inference,
AdamW 1e-4 with 500 warm-up steps and a cosine decay, EMA with power 0.75, batch 256, 3,000 epochs).

On action steps: that code asks for 8 of a horizon of 8 with 3 observation steps, but it executes
`action[n_obs_steps - 1 : n_obs_steps - 1 + n_action_steps]`, which a horizon of 8 cuts to 6. We say 6 and
refuse more than fit (`n_obs_steps - 1 + n_action_steps <= horizon`)."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class UnetConfig(_Strict):
    down_dims: tuple[int, ...] = Field(default=(512, 1024, 2048), min_length=1)
    kernel_size: int = Field(default=5, ge=1)
    n_groups: int = Field(default=8, ge=1)
    diffusion_step_embed_dim: int = Field(default=128, ge=2)
    cond_predict_scale: bool = True  # FiLM with scale and bias (DP's default), not bias only

    @model_validator(mode="after")
    def _groups_divide(self) -> UnetConfig:
        bad = [d for d in self.down_dims if d % self.n_groups]
        if bad:
            raise ValueError(f"down_dims {bad} are not multiples of n_groups={self.n_groups} (GroupNorm)")
        return self


class NoiseConfig(_Strict):
    num_train_timesteps: int = Field(default=100, ge=1)
    num_inference_steps: int = Field(default=10, ge=1)
    beta_schedule: Literal["squaredcos_cap_v2", "linear", "scaled_linear"] = "squaredcos_cap_v2"
    prediction_type: Literal["epsilon", "sample"] = "epsilon"
    clip_sample: bool = True

    @model_validator(mode="after")
    def _fewer_inference_steps(self) -> NoiseConfig:
        if self.num_inference_steps > self.num_train_timesteps:
            raise ValueError("num_inference_steps cannot exceed num_train_timesteps")
        return self


class TrainConfig(_Strict):
    epochs: int = Field(default=3000, ge=1)
    batch_size: int = Field(default=256, ge=1)
    lr: float = Field(default=1e-4, gt=0)
    weight_decay: float = Field(default=1e-6, ge=0)
    betas: tuple[float, float] = (0.95, 0.999)
    lr_warmup_steps: int = Field(default=500, ge=0)
    ema_power: float = Field(default=0.75, gt=0)
    ema_max_decay: float = Field(default=0.9999, gt=0, lt=1)
    checkpoint_every: int = Field(default=100, ge=1)  # epochs between kept checkpoints (the last one always)
    save_every: int = Field(default=10, ge=1)  # epochs between writes of the resumable latest.pt
    seed: int = 0
    episodes: int | None = Field(default=None, ge=1)  # the first N episodes of the data (None: all)


class PolicyConfig(_Strict):
    """What every policy has; dp.DPConfig and dp3.DP3Config add their encoders."""

    horizon: int = Field(default=8, ge=1)
    n_obs_steps: int = Field(default=3, ge=1)
    n_action_steps: int = Field(default=6, ge=1)
    state_dim: int = Field(default=26, ge=1)
    action_dim: int = Field(default=26, ge=1)
    unet: UnetConfig = UnetConfig()
    noise: NoiseConfig = NoiseConfig()
    train: TrainConfig = TrainConfig()
    # What the U-Net denoises: the joint targets as recorded ("absolute", DP's and DP3's), or each target minus
    # the last observed joint state ("relative", UMI's relative trajectories). The actions are normalized to
    # [-1, 1] over their range in the data, so the U-Net's error in radians scales with that range: close_drawer's
    # left-arm targets span 3.6-5.8 rad a joint (its grips are made in postures far apart), open_box_easy's
    # 0.2-1.0, and a DP3 that fits both about as well in [-1, 1] missed close_drawer's targets by 0.035-0.058 rad
    # a joint against open_box_easy's 0.002-0.017, where a steady 0.04 rad already loses most grips
    # (bench/replay_tolerance.py). Relative targets span the motion of one horizon instead. Measured there: the
    # relative frame cut that miss 2-3.5 times, but close_drawer's success only from 15% to 23%, and open_box_easy
    # scored 100% with either (docs/results/policies.md); the recipes keep the absolute frame until the whole
    # study is measured with it.
    action_frame: Literal["absolute", "relative"] = "absolute"
    # The hands' poses (`policies.hands`: each hand's position and orientation, in the world frame the point
    # cloud is in) fed beside the joint state. The joint state tells where a hand is only through the arm's
    # kinematics, which a network has to learn from the data; close_drawer's grips are made in postures up to
    # 5.6 rad apart on a joint (bench/demo_postures.py), where 50 demonstrations leave that map thinly sampled.
    # Measured there: no gain (DP3 fast on two DART draws, 33.3% against 35.0%, the same teacher-forced miss;
    # docs/results/policies.md), so it is off by default.
    observe_hands: bool = False

    @model_validator(mode="after")
    def _actions_fit(self) -> PolicyConfig:
        if self.action_frame == "relative" and self.state_dim != self.action_dim:
            raise ValueError(f"action_frame 'relative' needs one joint state per action (state_dim {self.state_dim}, "
                             f"action_dim {self.action_dim})")
        if self.n_obs_steps - 1 + self.n_action_steps > self.horizon:
            raise ValueError(f"n_obs_steps - 1 + n_action_steps = {self.n_obs_steps - 1 + self.n_action_steps} "
                             f"exceeds horizon {self.horizon}: the executed actions must lie in the predicted ones")
        levels = len(self.unet.down_dims) - 1  # the U-Net halves the sequence this many times
        if self.horizon % (1 << levels):
            raise ValueError(f"horizon {self.horizon} must be divisible by 2**{levels} for "
                             f"{len(self.unet.down_dims)} U-Net levels")
        return self
