"""No module outside humanoidgen/robots/ names a robot's link, joint or finger link: those names live in the robot
and hand files (robots/<robot>/robot.yaml, robots/hands/<hand>.yaml), and code reads them from there (through
`sim.layout`'s derived names or a `robots.Robot`).

What is scanned: every string in the code of every module (f-string parts included; docstrings and comments are
prose, not names), the reference plans under tasks/specs/ included. What counts as a robot's name: every joint
and body its files give (arms, welded joints, root, feet, torso, hand mounts, camera bodies, each hand joint and
finger link), with and without its side prefix (`left_`, `right_`, the hands' `L_` / `R_`), so that
f"{side}_wrist_yaw_link" is caught as well as "left_wrist_yaw_link".

Not robot names (decided, docs/guides/robots.md): the hand's API names that plans use, its annotations
("right_thumb_2_index", "grasp_point_base_left_hand"), its end-effector frames ("r_hand_base_link", the planner
API's names, which the robot file gives as `hands.<side>.frame`), its postures and bare finger words ("thumb",
"index": the shared hand vocabulary `hand_ops.finger_contacts` reports).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import humanoidgen
from humanoidgen.robots import load_robot, robot_names

ROOT = Path(humanoidgen.__file__).resolve().parent
# Documented exceptions: "path relative to humanoidgen/": reason. Keep this short; none are needed today.
ALLOWED: dict[str, str] = {}


def robot_model_names() -> set[str]:
    names: set[str] = set()
    for robot_name in robot_names():
        robot = load_robot(robot_name)
        found = robot.model_names()
        prefixes = ("left_", "right_", *(f"{p}_" for p in robot.hand_prefix.values()))
        for name in found["joints"] + found["bodies"]:
            stems = {name, *(name[len(p):] for p in prefixes if name.startswith(p))}
            # "shoulder_pitch" of f"{side}_shoulder_pitch_joint" too; not one-word stems ("torso": prose)
            stems |= {s.removesuffix(x) for s in stems for x in ("_joint", "_link") if "_" in s.removesuffix(x)}
            names |= stems
    return names


def hand_prefixes() -> set[str]:
    """The hands' name prefixes as strings of their own ("L_"): what code that picks hand joints by prefix writes."""
    return {f"{p}_" for r in robot_names() for p in load_robot(r).hand_prefix.values()}


def _docstrings(tree: ast.AST) -> set[int]:
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                out.add(id(first.value))
    return out


def code_strings(path: Path) -> list[tuple[int, str]]:
    """(line, text) of every string constant in `path` but its docstrings."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skip = _docstrings(tree)
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in skip]


def name_pattern(names: set[str]) -> re.Pattern:
    # A name inside a longer identifier-like word does not count ("pelvis" in "pelvises" would not), an
    # underscore before it does ("_wrist_yaw_link" of an f-string).
    alternatives = "|".join(re.escape(n) for n in sorted(names, key=len, reverse=True))
    return re.compile(rf"(?<![A-Za-z0-9])(?:{alternatives})(?![A-Za-z0-9])")


def test_the_scan_knows_the_robots_names():
    names = robot_model_names()
    for expected in ("left_wrist_yaw_link", "wrist_yaw_link", "thumb_distal", "L_index_proximal_joint",
                     "index_proximal_joint", "pelvis", "torso_link", "floating_base_joint", "left_ankle_roll_link",
                     "shoulder_pitch", "wrist_yaw"):
        assert expected in names
    pattern = name_pattern(names)
    assert pattern.search('f"{side}_wrist_yaw_link"') and pattern.search("R_thumb_distal")
    assert not pattern.search("right_thumb_2_index") and not pattern.search("r_hand_base_link")
    assert "torso" not in names and "L_" in hand_prefixes()


def test_no_module_outside_robots_names_a_robot_link_joint_or_finger():
    pattern, prefixes = name_pattern(robot_model_names()), hand_prefixes()
    hits = []
    for path in sorted(ROOT.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel.startswith("robots/") or rel in ALLOWED:
            continue
        for line, text in code_strings(path):
            if m := pattern.search(text):
                hits.append(f"humanoidgen/{rel}:{line} names {m.group(0)!r} ({text[:60]!r})")
            elif text in prefixes:
                hits.append(f"humanoidgen/{rel}:{line} names the hand prefix {text!r}")
    assert not hits, ("robot names in code; read them from the robot file (sim.layout / robots.Robot):\n"
                      + "\n".join(hits))


def test_allowed_exceptions_are_real_and_explained():
    for rel, reason in ALLOWED.items():
        assert (ROOT / rel).is_file(), rel
        assert len(reason) > 20, f"say why {rel} may name the robot"
