"""Where recorded point clouds begin above the table top: the number on its own, without the point-cloud code
(numba), for the settings that name it (`RecorderConfig`, `TaskEnvConfig`) in processes that never fuse a cloud."""

# The recorded clouds' floor, metres above the table top: the table's surface is left out (DP3's authors crop the
# table and the ground away too) because farthest-point sampling spreads its points evenly over what it is given,
# and the table took two thirds of them (measured on close_drawer's demonstrations: 66% of the first 256 within 1 mm
# of z = 0), leaving a handle a policy must grip a handful. 5 mm clears the rendered table (its points lie within
# 1 mm of 0) and keeps all but an object's lowest 5 mm.
CLOUD_FLOOR = 0.005
# What datasets recorded before the floor was a setting used: the table's surface kept (depth noise margin).
TABLE_CLOUD_FLOOR = -0.01
