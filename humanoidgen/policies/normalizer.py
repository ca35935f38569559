"""Min-max normalization to [-1, 1] per feature, fitted on the training data and saved in the checkpoint so
a loaded policy normalizes exactly as it was trained (DP's LinearNormalizer in 'limits' mode)."""

from __future__ import annotations

import numpy as np
import torch
from torch import nn

RANGE_EPS = 1e-4  # features that never change (a joint the task does not move) map to 0, not to noise


class MinMaxNormalizer(nn.Module):
    """Per-key, per-last-axis-feature scale and offset; buffers, so they travel with `state_dict()`."""

    def __init__(self, dims: dict[str, int]) -> None:
        super().__init__()
        self.keys = tuple(sorted(dims))
        for k in self.keys:
            self.register_buffer(_name(k, "scale"), torch.ones(dims[k]))
            self.register_buffer(_name(k, "offset"), torch.zeros(dims[k]))

    def fit(self, data: dict[str, np.ndarray]) -> MinMaxNormalizer:
        for k in self.keys:
            x = np.asarray(data[k], np.float64).reshape(-1, data[k].shape[-1])
            lo, hi = x.min(axis=0), x.max(axis=0)
            span = hi - lo
            flat = span < RANGE_EPS
            scale = np.where(flat, 1.0, 2.0 / np.where(flat, 1.0, span))
            offset = np.where(flat, -lo, -1.0 - lo * scale)  # a constant feature -> 0
            getattr(self, _name(k, "scale")).copy_(torch.as_tensor(scale, dtype=torch.float32))
            getattr(self, _name(k, "offset")).copy_(torch.as_tensor(offset, dtype=torch.float32))
        return self

    def normalize(self, key: str, x: torch.Tensor) -> torch.Tensor:
        return x * getattr(self, _name(key, "scale")) + getattr(self, _name(key, "offset"))

    def unnormalize(self, key: str, x: torch.Tensor) -> torch.Tensor:
        return (x - getattr(self, _name(key, "offset"))) / getattr(self, _name(key, "scale"))


def _name(key: str, what: str) -> str:
    return f"{key}__{what}"
