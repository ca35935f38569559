"""Beyond the table: room-level scenes (the paper's O -> O' scene scaling) and visual randomization."""
