"""DP3's encoder: a per-point MLP (Linear-LayerNorm-ReLU) max-pooled over the cloud and projected to a small
feature (LayerNorm), concatenated with an MLP of the joint state (and the hands' poses, `observe_hands`)."""

from __future__ import annotations

import torch
from torch import nn

from humanoidgen.policies.diffusion import DiffusionPolicy
from humanoidgen.policies.dp3.config import DP3Config


class PointEncoder(nn.Module):
    def __init__(self, cfg: DP3Config) -> None:
        super().__init__()
        layers: list[nn.Module] = []
        c = 3
        for width in cfg.point_mlp:
            layers += [nn.Linear(c, width), nn.LayerNorm(width), nn.ReLU()]
            c = width
        self.mlp = nn.Sequential(*layers)
        self.project = nn.Sequential(nn.Linear(c, cfg.encoder_output_dim), nn.LayerNorm(cfg.encoder_output_dim))

    def forward(self, points: torch.Tensor) -> torch.Tensor:  # (B, N, 3) -> (B, out)
        return self.project(self.mlp(points).max(dim=1).values)


def state_mlp(dim_in: int, widths: tuple[int, ...]) -> nn.Sequential:
    layers: list[nn.Module] = []
    for i, width in enumerate(widths):
        layers.append(nn.Linear(dim_in, width))
        if i < len(widths) - 1:
            layers.append(nn.ReLU())
        dim_in = width
    return nn.Sequential(*layers)


class DP3Policy(DiffusionPolicy):
    name = "dp3"
    obs_keys = ("state", "point_cloud")
    cfg: DP3Config

    def __init__(self, cfg: DP3Config) -> None:
        self._feat = cfg.encoder_output_dim + cfg.state_mlp[-1]
        super().__init__(cfg, {"state": cfg.state_dim, "action": cfg.action_dim, "point_cloud": 3})
        self.points = PointEncoder(cfg)
        self.state = state_mlp(self.proprio_dim(cfg), cfg.state_mlp)

    def feature_dim(self) -> int:
        return self._feat

    def normalize_obs(self, obs: dict[str, torch.Tensor]) -> dict[str, torch.Tensor]:
        pc = obs["point_cloud"][..., : self.cfg.num_points, :3].float()
        return {**super().normalize_obs(obs), "point_cloud": self.normalizer.normalize("point_cloud", pc)}

    def encode_steps(self, obs: dict[str, torch.Tensor]) -> torch.Tensor:
        return torch.cat([self.points(obs["point_cloud"]), self.state(self.proprio(obs))], dim=-1)
