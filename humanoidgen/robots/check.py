"""Checking a robot file against its model files: every joint and body it names is in the MJCF, every joint
of the MJCF is an arm joint, a hand joint or welded, the URDF couples the hands' followers, and every model
file has the sha256 the checksums file gives. Errors are lines naming the file and the field."""

from __future__ import annotations

from pathlib import Path

from humanoidgen.robots.checksums import parse_sums, sha256_file
from humanoidgen.robots.mimic import read_mimics
from humanoidgen.robots.loader import Robot, RobotFileError, load_robot
from humanoidgen.robots.schema import SIDE_NAMES


def _model_names(assets_root: Path, robot: Robot) -> tuple[list[str], list[str]]:
    from humanoidgen.robots.assemble import model_names

    return model_names(assets_root, robot)


def _field_names(robot: Robot) -> list[tuple[str, str, str]]:
    """(field, kind, name) for every model name the robot and hand files give."""
    d, out = robot.data, []
    for s in SIDE_NAMES:
        for k, j in enumerate(d.arms[s]):
            out += [(f"arms.{s}.{k}.joint", "joint", j.joint), (f"arms.{s}.{k}.link", "body", j.link)]
        out.append((f"hands.{s}.mount", "body", robot.hand_mount(s)))
        out += [(f"{robot.hand.path.name}: joints.{k}.stem ({s})", "joint", n)
                for k, n in enumerate(robot.hand_joints[s])]
        out += [(f"{robot.hand.path.name}: fingers.{f} ({s})", "body", robot.hand_link(s, link))
                for f, links in robot.hand.data.fingers.items() for link in links]
    out += [(f"weld.{k}", "joint", n) for k, n in enumerate(d.weld)]
    out += [("stand.root_body", "body", d.stand.root_body)]
    out += [(f"stand.feet.{k}", "body", n) for k, n in enumerate(d.stand.feet)]
    out += [(f"torso_bodies.{k}", "body", n) for k, n in enumerate(d.torso_bodies)]
    out += [(f"no_collision.{w}.{k}", "body", n) for w in ("subtrees", "bodies")
            for k, n in enumerate(getattr(d.no_collision, w))]
    out += [(f"cameras.{k}.body", "body", c.body) for k, c in enumerate(d.cameras) if c.body is not None]
    return out


def check_model(robot: Robot, model_dir: Path, checksums: bool = True) -> list[str]:
    """What does not fit between `robot`'s files and the model files in `model_dir` (and, for hands from another
    robot's model, that model's folder beside it): one line each."""
    path, problems = robot.path, []
    assets_root = model_dir.parent
    sums = parse_sums(robot.sums_path.read_text("utf-8"))
    for name in (robot.data.model.mjcf, robot.data.model.urdf):
        if name is not None and name not in sums:
            problems.append(f"{path}: model: {name} has no line in {robot.data.model.checksums}")
    mjcf = model_dir / robot.data.model.mjcf
    if not mjcf.is_file():
        return [*problems, f"{path}: model.mjcf: no file {mjcf}"]
    if checksums:
        for name, digest in sums.items():
            f = model_dir / name
            if not f.is_file():
                problems.append(f"{path}: model.checksums: {name} is missing from {model_dir}")
            elif sha256_file(f) != digest:
                problems.append(f"{path}: model.checksums: {name} does not match its sha256 (a checksum mismatch)")
    source = robot.hand_source
    if source is not None and not (assets_root / source.data.model.folder / source.data.model.mjcf).is_file():
        return [*problems, f"{path}: hands.source.robot: no model of {source.name} in {assets_root} "
                           f"(`hgen assets fetch --robot {robot.name}` fetches both)"]
    joints, bodies = _model_names(assets_root, robot)
    have = {"joint": set(joints), "body": set(bodies)}
    for fld, kind, name in _field_names(robot):
        if name not in have[kind]:
            problems.append(f"{path}: {fld}: no {kind} {name!r} in {mjcf.name}")
    arm = {j for s in SIDE_NAMES for j in robot.arm_joints[s]}
    for j in joints:
        if j not in arm and j not in robot.data.weld and not robot.is_hand_name(j):
            problems.append(f"{path}: weld: joint {j!r} of {mjcf.name} is neither an arm joint, a hand joint "
                            f"nor welded")
    if robot.hand.data.followers == "urdf_mimic":
        problems += _check_mimics(robot, assets_root, set(joints))
    return problems


def _check_mimics(robot: Robot, assets_root: Path, joints: set[str]) -> list[str]:
    """Every hand joint that no action entry drives follows an actuated one of its hand by a URDF <mimic>."""
    from humanoidgen.robots.assemble import mimic_urdf

    path, urdf = robot.path, mimic_urdf(assets_root, robot)
    hand = robot.hand.path.name
    if urdf is None:
        return [f"{path}: model.urdf: {hand} couples its followers by the URDF's <mimic> tags: name the URDF"]
    urdf_name = urdf.name
    if not urdf.is_file():
        return [f"{path}: model.urdf: no file {urdf}"]
    mimics = {m.follower: m.driver for m in read_mimics(urdf)}
    problems = []
    for s in SIDE_NAMES:
        actuated = set(robot.hand_joints[s])
        for j in sorted(j for j in joints if robot.is_hand_name(j, s) and j not in actuated):
            if mimics.get(j) not in actuated:
                problems.append(f"{path}: {hand}: followers: {s} hand joint {j!r} follows no actuated joint in "
                                f"{urdf_name}")
    return problems


def check(path: Path | str, assets_root: Path | None = None, checksums: bool = True) -> list[str]:
    """Validate the robot file at `path` (and its hand file); with `assets_root`, against the model files too."""
    try:
        robot = load_robot(path, cached=False)
    except RobotFileError as exc:
        return [str(exc)]
    if assets_root is None:
        return []
    return check_model(robot, Path(assets_root) / robot.data.model.folder, checksums)
