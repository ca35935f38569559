"""The conditional 1D temporal U-Net of Diffusion Policy (Chi et al. 2023): residual 1D-conv blocks over the
action sequence, each modulated (FiLM) by the diffusion step's embedding concatenated with the observation
features, two halvings of the sequence down and back up with skip connections."""

from __future__ import annotations

import math

import torch
from torch import nn

from humanoidgen.policies.config import UnetConfig


class SinusoidalStepEmbedding(nn.Module):
    def __init__(self, dim: int) -> None:
        super().__init__()
        self.dim = dim

    def forward(self, t: torch.Tensor) -> torch.Tensor:
        half = self.dim // 2
        freqs = torch.exp(torch.arange(half, device=t.device) * -(math.log(10000) / (half - 1)))
        angles = t.float()[:, None] * freqs[None]
        return torch.cat([angles.sin(), angles.cos()], dim=-1)


class ConvBlock(nn.Sequential):
    """Conv1d -> GroupNorm -> Mish."""

    def __init__(self, c_in: int, c_out: int, kernel: int, groups: int) -> None:
        super().__init__(nn.Conv1d(c_in, c_out, kernel, padding=kernel // 2), nn.GroupNorm(groups, c_out), nn.Mish())


class CondResidualBlock(nn.Module):
    def __init__(self, c_in: int, c_out: int, cond_dim: int, kernel: int, groups: int, predict_scale: bool) -> None:
        super().__init__()
        self.blocks = nn.ModuleList([ConvBlock(c_in, c_out, kernel, groups), ConvBlock(c_out, c_out, kernel, groups)])
        self.c_out, self.predict_scale = c_out, predict_scale
        self.cond = nn.Sequential(nn.Mish(), nn.Linear(cond_dim, c_out * 2 if predict_scale else c_out))
        self.skip = nn.Conv1d(c_in, c_out, 1) if c_in != c_out else nn.Identity()

    def forward(self, x: torch.Tensor, cond: torch.Tensor) -> torch.Tensor:
        out = self.blocks[0](x)
        film = self.cond(cond)[..., None]
        if self.predict_scale:
            scale, bias = film[:, : self.c_out], film[:, self.c_out:]
            out = scale * out + bias
        else:
            out = out + film
        return self.blocks[1](out) + self.skip(x)


class ConditionalUnet1D(nn.Module):
    """`forward(sample (B, T, action_dim), timestep (B,), global_cond (B, cond_dim)) -> (B, T, action_dim)`."""

    def __init__(self, action_dim: int, global_cond_dim: int, cfg: UnetConfig) -> None:
        super().__init__()
        dims = [action_dim, *cfg.down_dims]
        k, g, s = cfg.kernel_size, cfg.n_groups, cfg.cond_predict_scale
        step_dim = cfg.diffusion_step_embed_dim
        self.step_encoder = nn.Sequential(SinusoidalStepEmbedding(step_dim), nn.Linear(step_dim, step_dim * 4),
                                          nn.Mish(), nn.Linear(step_dim * 4, step_dim))
        cond_dim = step_dim + global_cond_dim
        pairs = list(zip(dims[:-1], dims[1:]))
        self.down = nn.ModuleList()
        for i, (c_in, c_out) in enumerate(pairs):
            last = i == len(pairs) - 1
            self.down.append(nn.ModuleList([
                CondResidualBlock(c_in, c_out, cond_dim, k, g, s), CondResidualBlock(c_out, c_out, cond_dim, k, g, s),
                nn.Conv1d(c_out, c_out, 3, stride=2, padding=1) if not last else nn.Identity()]))
        mid = dims[-1]
        self.mid = nn.ModuleList([CondResidualBlock(mid, mid, cond_dim, k, g, s) for _ in range(2)])
        self.up = nn.ModuleList()
        for c_in, c_out in reversed(pairs[1:]):  # each undoes one halving
            self.up.append(nn.ModuleList([
                CondResidualBlock(c_out * 2, c_in, cond_dim, k, g, s), CondResidualBlock(c_in, c_in, cond_dim, k, g, s),
                nn.ConvTranspose1d(c_in, c_in, 4, stride=2, padding=1)]))
        self.final = nn.Sequential(ConvBlock(dims[1], dims[1], k, g), nn.Conv1d(dims[1], action_dim, 1))

    def forward(self, sample: torch.Tensor, timestep: torch.Tensor, global_cond: torch.Tensor) -> torch.Tensor:
        x = sample.transpose(1, 2)  # (B, C, T): convolutions run along time
        if timestep.ndim == 0:
            timestep = timestep.expand(x.shape[0])
        cond = torch.cat([self.step_encoder(timestep.to(x.device)), global_cond], dim=-1)
        skips = []
        for res1, res2, down in self.down:
            x = res2(res1(x, cond), cond)
            skips.append(x)
            x = down(x)
        for block in self.mid:
            x = block(x, cond)
        for res1, res2, up in self.up:
            x = torch.cat([x, skips.pop()], dim=1)
            x = up(res2(res1(x, cond), cond))
        return self.final(x).transpose(1, 2)
