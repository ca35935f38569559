# rule probe (item 1): imports. The prompt says "Do not import anything"; LLMs still open steps with
# `import numpy as np` / `import math`. Otherwise the plan is the prompt's worked example: pinch cube 1, lift,
# put it on its target on cube 0, let go, go home.
# style: our `# step:` blocks, each starting with the imports an LLM habitually writes.
# step: pinch cube 1 with the right hand
import numpy as np
planner.hand_pre_pinch("right")
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="pinch", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=False)
planner.hand_pinch("right", pinch_object="cube", obj_id=1)

# step: lift cube 1 by 8 cm
import numpy as np
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="move", hand_name="right",
                                 relative_obj_name="cube", relative_obj_id=1, relative_p=np.array([0.0, 0.0, 0.08]))
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)

# step: place cube 1 on cube 0 and release
import math
c = planner.generate_constraints(obj_name="cube", obj_id=1, action="target", hand_name="right")
_, pose = planner.generate_end_effector_pose(c, hand_name="right")
planner.move_to_pose_with_screw(pose, "right", attach_obj=True, object_name="cube", object_id=1)
planner.open_hand("right")

# step: return the right hand
planner.move_to_pose_with_screw(planner.right_hand_init_pose, "right")
