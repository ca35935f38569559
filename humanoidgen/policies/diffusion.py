"""What DP and DP3 share: an observation encoder (the subclass's) conditions a 1D U-Net that denoises a
normalized action sequence; DDPM noising for training and DDIM sampling for inference, both from diffusers.

Observations are dicts of tensors shaped (B, n_obs_steps, ...) with the zarr's names (state, img,
point_cloud); actions (B, horizon, action_dim). `predict_action` returns unnormalized actions, the full
predicted sequence and the `n_action_steps` to execute (from the current observation on)."""

from __future__ import annotations

import torch
import torch.nn.functional as F
from diffusers import DDIMScheduler, DDPMScheduler
from torch import nn

from humanoidgen.policies.config import PolicyConfig
from humanoidgen.policies.hands import HAND_FEATURES
from humanoidgen.policies.normalizer import MinMaxNormalizer
from humanoidgen.policies.unet import ConditionalUnet1D


class DiffusionPolicy(nn.Module):
    name = "base"
    obs_keys: tuple[str, ...] = ("state",)

    def __init__(self, cfg: PolicyConfig, norm_dims: dict[str, int]) -> None:
        super().__init__()
        self.cfg = cfg
        if cfg.action_frame == "relative":  # the recorded targets' range too: what the random baseline draws in
            norm_dims = {**norm_dims, "target": cfg.action_dim}
        if cfg.observe_hands:
            norm_dims = {**norm_dims, "hands": HAND_FEATURES}
        self.obs_keys = self.inputs_for(cfg)
        self.normalizer = MinMaxNormalizer(norm_dims)
        self.unet = ConditionalUnet1D(cfg.action_dim, self.feature_dim() * cfg.n_obs_steps, cfg.unet)
        n = cfg.noise
        common = dict(num_train_timesteps=n.num_train_timesteps, beta_start=1e-4, beta_end=0.02,
                      beta_schedule=n.beta_schedule, clip_sample=n.clip_sample, prediction_type=n.prediction_type)
        self.train_scheduler = DDPMScheduler(variance_type="fixed_small", **common)
        self.sample_scheduler = DDIMScheduler(set_alpha_to_one=True, steps_offset=0, **common)

    @classmethod
    def inputs_for(cls, cfg: PolicyConfig) -> tuple[str, ...]:
        """The observations (the zarr's names) a policy of this kind with `cfg` reads."""
        return cls.obs_keys + (("hands",) if cfg.observe_hands else ())

    @staticmethod
    def proprio_dim(cfg: PolicyConfig) -> int:
        """Numbers per observation step of `proprio`: the joint state, and the hands' poses where observed."""
        return cfg.state_dim + (HAND_FEATURES if cfg.observe_hands else 0)

    def proprio(self, obs: dict[str, torch.Tensor]) -> torch.Tensor:
        """The normalized joint state, with the hands' poses after it where the policy observes them."""
        return torch.cat([obs["state"], obs["hands"]], dim=-1) if self.cfg.observe_hands else obs["state"]

    # -- subclasses ----------------------------------------------------------------------------------------
    def feature_dim(self) -> int:
        """Features per observation step."""
        raise NotImplementedError

    def encode_steps(self, obs: dict[str, torch.Tensor]) -> torch.Tensor:
        """(B*n_obs, ...) per key -> (B*n_obs, feature_dim); inputs already normalized."""
        raise NotImplementedError

    def normalize_obs(self, obs: dict[str, torch.Tensor]) -> dict[str, torch.Tensor]:
        out = {"state": self.normalizer.normalize("state", obs["state"].float())}
        if self.cfg.observe_hands:
            out["hands"] = self.normalizer.normalize("hands", obs["hands"].float())
        return out

    # -- shared --------------------------------------------------------------------------------------------
    def global_cond(self, obs: dict[str, torch.Tensor]) -> torch.Tensor:
        obs = {k: v[:, : self.cfg.n_obs_steps] for k, v in obs.items() if k in self.obs_keys}
        b = next(iter(obs.values())).shape[0]
        flat = {k: v.reshape(-1, *v.shape[2:]) for k, v in self.normalize_obs(obs).items()}
        return self.encode_steps(flat).reshape(b, -1)

    def _origin(self, state: torch.Tensor) -> torch.Tensor | None:
        """Where the denoised actions are measured from (`PolicyConfig.action_frame`): None (as recorded), or the
        last observed joint state of `state` (B, n_obs_steps, state_dim), as (B, 1, state_dim)."""
        if self.cfg.action_frame == "absolute":
            return None
        last = self.cfg.n_obs_steps - 1
        return state[:, last:last + 1]

    def framed(self, action: torch.Tensor, state: torch.Tensor) -> torch.Tensor:
        """Actions (B, T, action_dim) in the frame the U-Net denoises."""
        origin = self._origin(state)
        return action if origin is None else action - origin.to(action.dtype)

    def unframed(self, action: torch.Tensor, state: torch.Tensor) -> torch.Tensor:
        """The inverse of `framed`: joint targets to execute."""
        origin = self._origin(state)
        return action if origin is None else action + origin.to(action.dtype)

    def compute_loss(self, batch: dict[str, torch.Tensor]) -> torch.Tensor:
        action = self.normalizer.normalize("action", self.framed(batch["action"].float(), batch["state"]))
        cond = self.global_cond(batch)
        noise = torch.randn_like(action)
        t = torch.randint(0, self.train_scheduler.config.num_train_timesteps, (action.shape[0],),
                          device=action.device)
        noisy = self.train_scheduler.add_noise(action, noise, t)
        pred = self.unet(noisy, t, cond)
        target = noise if self.cfg.noise.prediction_type == "epsilon" else action
        return F.mse_loss(pred, target)

    @torch.no_grad()
    def predict_action(self, obs: dict[str, torch.Tensor], generator: torch.Generator | None = None
                       ) -> dict[str, torch.Tensor]:
        cond = self.global_cond(obs)
        cfg = self.cfg
        x = torch.randn((cond.shape[0], cfg.horizon, cfg.action_dim), generator=generator,
                        device=cond.device if generator is None else generator.device).to(cond.device)
        sched = self.sample_scheduler
        sched.set_timesteps(cfg.noise.num_inference_steps)
        for t in sched.timesteps:
            out = self.unet(x, t.to(cond.device), cond)
            x = sched.step(out, t, x, generator=generator).prev_sample
        seq = self.unframed(self.normalizer.unnormalize("action", x), obs["state"])
        start = cfg.n_obs_steps - 1
        return {"action_pred": seq, "action": seq[:, start: start + cfg.n_action_steps]}
