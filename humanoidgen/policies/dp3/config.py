"""DP3 (Ze et al. 2024): a cropped, downsampled point cloud (xyz) and the joint state. Defaults from the DP3
code's dp3.yaml as RoboTwin runs it: the 'mlp' point encoder with 64 output features, a 64-64 state MLP,
`sample` prediction, a 512/1024/2048 U-Net."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from humanoidgen.policies.config import NoiseConfig, PolicyConfig, UnetConfig


class DP3Config(PolicyConfig):
    policy: Literal["dp3"] = "dp3"
    num_points: int = Field(default=1024, ge=1)
    encoder_output_dim: int = Field(default=64, ge=1)
    point_mlp: tuple[int, ...] = (64, 128, 256)
    state_mlp: tuple[int, ...] = (64, 64)
    unet: UnetConfig = UnetConfig(down_dims=(512, 1024, 2048))
    noise: NoiseConfig = NoiseConfig(prediction_type="sample")
