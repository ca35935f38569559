"""DP's image encoder: torchvision's ResNet-18 (no pretrained weights) with every BatchNorm replaced by
GroupNorm, its classifier removed (512 features), fed a random crop in training and the centre crop at
inference; its features are concatenated with the normalized joint state."""

from __future__ import annotations

import torch
import torchvision
from torch import nn

from humanoidgen.policies.diffusion import DiffusionPolicy
from humanoidgen.policies.dp.config import DPConfig

RESNET_FEATURES = 512


def resnet18_groupnorm(group_channels: int) -> nn.Module:
    net = torchvision.models.resnet18(weights=None, norm_layer=lambda c: nn.GroupNorm(max(1, c // group_channels), c))
    net.fc = nn.Identity()
    return net


class DPPolicy(DiffusionPolicy):
    name = "dp"
    obs_keys = ("state", "img")
    cfg: DPConfig

    def __init__(self, cfg: DPConfig) -> None:
        super().__init__(cfg, {"state": cfg.state_dim, "action": cfg.action_dim})
        self.encoder = resnet18_groupnorm(cfg.group_channels)

    def feature_dim(self) -> int:
        return RESNET_FEATURES + self.proprio_dim(self.cfg)

    def normalize_obs(self, obs: dict[str, torch.Tensor]) -> dict[str, torch.Tensor]:
        img = obs["img"]  # (..., H, W, 3) uint8, already at image_size
        img = img.movedim(-1, -3).float() / 127.5 - 1.0  # [0, 255] -> [-1, 1], channels first
        return {**super().normalize_obs(obs), "img": img}

    def encode_steps(self, obs: dict[str, torch.Tensor]) -> torch.Tensor:
        return torch.cat([self.encoder(self._crop(obs["img"])), self.proprio(obs)], dim=-1)

    def _crop(self, img: torch.Tensor) -> torch.Tensor:
        ch, cw = self.cfg.crop_size
        h, w = img.shape[-2:]
        if not self.training:
            top, left = (h - ch) // 2, (w - cw) // 2
            return img[..., top: top + ch, left: left + cw]
        # One random offset per image (DP's CropRandomizer), gathered with unfold-free indexing.
        b = img.shape[0]
        tops = torch.randint(0, h - ch + 1, (b,), device=img.device)
        lefts = torch.randint(0, w - cw + 1, (b,), device=img.device)
        rows = (tops[:, None] + torch.arange(ch, device=img.device))[:, None, :, None]
        cols = (lefts[:, None] + torch.arange(cw, device=img.device))[:, None, None, :]
        idx = torch.arange(b, device=img.device)[:, None, None, None]
        chans = torch.arange(img.shape[1], device=img.device)[None, :, None, None]
        return img[idx, chans, rows, cols]


def resize_images(frames, size: tuple[int, int], chunk: int = 256, stop: int | None = None) -> torch.Tensor:
    """(N, H, W, 3) uint8 frames (numpy or zarr; the first `stop`) -> (N, h, w, 3) uint8 at `size`,
    antialiased. Read a chunk at a time: a zarr of full-size frames need not fit in memory."""
    import numpy as np

    n = frames.shape[0] if stop is None else min(stop, frames.shape[0])  # zarr arrays have no len()
    out = []
    for i in range(0, n, chunk):
        x = torch.as_tensor(np.asarray(frames[i: min(i + chunk, n)])).movedim(-1, 1).float()
        if tuple(x.shape[-2:]) != tuple(size):
            x = torch.nn.functional.interpolate(x, size=size, mode="bilinear", antialias=True, align_corners=False)
        out.append(x.round().clamp(0, 255).to(torch.uint8).movedim(1, -1))
    return torch.cat(out) if out else torch.zeros((0, *size, 3), dtype=torch.uint8)
