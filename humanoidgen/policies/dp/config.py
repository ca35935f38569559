"""Diffusion Policy (Chi et al. 2023) on the head camera's RGB and the joint state. Defaults from DP's
image U-Net config: ResNet-18 from scratch with GroupNorm (16 channels a group) in place of BatchNorm, a
random crop in training (the centre crop at inference), `epsilon` prediction, a 512/1024/2048 U-Net. Images
are resized to `image_size` once, when the data is loaded."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from humanoidgen.policies.config import PolicyConfig, UnetConfig


class DPConfig(PolicyConfig):
    policy: Literal["dp"] = "dp"
    camera: str = "head"  # which camera the zarr's data/img holds (its export's --camera)
    image_size: tuple[int, int] = (120, 160)  # (height, width) after resizing the recorded frames
    crop_size: tuple[int, int] = (108, 144)
    unet: UnetConfig = UnetConfig(down_dims=(512, 1024, 2048))
    group_channels: int = Field(default=16, ge=1)

    @model_validator(mode="after")
    def _crop_fits(self) -> DPConfig:
        if any(c > s for c, s in zip(self.crop_size, self.image_size)):
            raise ValueError(f"crop_size {self.crop_size} is larger than image_size {self.image_size}")
        return self
