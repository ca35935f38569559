"""Where recorded point clouds begin above the table top, and how far around the hands a focused cloud looks: the
numbers on their own, without the point-cloud code (numba), for the settings that name them (`RecorderConfig`,
`TaskEnvConfig`) in processes that never fuse a cloud."""

# The recorded clouds' floor, metres above the table top: the table's surface is left out (DP3's authors crop the
# table and the ground away too) because farthest-point sampling spreads its points evenly over what it is given,
# and the table took two thirds of them (measured on close_drawer's demonstrations: 66% of the first 256 within 1 mm
# of z = 0), leaving a handle a policy must grip a handful. 5 mm clears the rendered table (its points lie within
# 1 mm of 0) and keeps all but an object's lowest 5 mm.
CLOUD_FLOOR = 0.005
# What datasets recorded before the floor was a setting used: the table's surface kept (depth noise margin).
TABLE_CLOUD_FLOOR = -0.01

# A focused cloud (`point_cloud_near_hands` > 0) draws that share of its points from within this distance of either
# hand's grasp point (`episodes.render_replay.focus_points`): the Inspire hand's fingertips are about 0.1 m from it,
# so the ball holds the fingers and what they are about to close on.
NEAR_HANDS_RADIUS = 0.1


def check_near_hands(share: float) -> None:
    """Raise ValueError unless `share` (of a cloud's points drawn near the hands) is in [0, 1)."""
    if not 0.0 <= share < 1.0:
        raise ValueError(f"point_cloud_near_hands must be in [0, 1) (a share of the cloud's points), got {share}")
