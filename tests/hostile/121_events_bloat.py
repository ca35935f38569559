# attempts: planner.events.append of a 200 MB string (the result channel, not stdout)
# effect: output
# needs: planner
planner.events.append('G' * 200_000_000)
