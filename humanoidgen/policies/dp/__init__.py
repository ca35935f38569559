"""Diffusion Policy: head-camera RGB + joint state."""
