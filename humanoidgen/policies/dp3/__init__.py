"""DP3: point cloud + joint state."""
