"""Short digests of what a simulation's physics depends on besides its state: the model's physical fields
(gravity, timestep, masses, friction, joint ranges, damping, equality constraints, actuator gains, ...) and
the inputs a program can set on `MjData` outside the robot's commands (applied forces, mocap poses,
equality activation).

The replay that judges an episode (`episodes.replay`) runs on a model built afresh from the task; a plan's
worker reports its own digests at the end, and where they differ the verdict can name what the plan edited
("opt.gravity, body_mass") instead of only that the simulation went another way. The worker's digests are
its word, used only to explain a rejection, never to accept anything.
"""

from __future__ import annotations

import hashlib

import mujoco
import numpy as np

# Large arrays that hold geometry and assets (meshes, textures, bounding-volume trees) and names: editing
# them is no way to change an episode's outcome that a state write would not also show, and hashing them
# costs tenths of a second per scene.
_SKIPPED_PREFIXES = ("mesh_", "tex_", "skin_", "hfield_", "flex_", "bvh_", "oct_", "name_", "names", "text_",
                     "tuple_", "key_", "plugin", "paths", "B_", "M_", "D_", "mapM2D", "mapD2M")
_OPT_FIELDS = ("timestep", "gravity", "wind", "magnetic", "density", "viscosity", "impratio", "o_margin",
               "o_solref", "o_solimp", "o_friction", "integrator", "cone", "jacobian", "solver", "iterations",
               "tolerance", "ls_iterations", "ls_tolerance", "noslip_iterations", "noslip_tolerance",
               "disableflags", "enableflags", "disableactuator")
DATA_FIELDS = ("qfrc_applied", "xfrc_applied", "mocap_pos", "mocap_quat", "eq_active", "userdata")


def _digest(value: object) -> str:
    data = np.ascontiguousarray(np.asarray(value)).tobytes()
    return hashlib.blake2b(data, digest_size=8).hexdigest()


def _model_fields(model: mujoco.MjModel) -> list[str]:
    return [n for n in dir(model) if not n.startswith("_") and not n.startswith(_SKIPPED_PREFIXES)
            and isinstance(getattr(model, n, None), np.ndarray)]


def fingerprint(model: mujoco.MjModel, data: mujoco.MjData | None = None) -> dict[str, str]:
    """Field name -> digest, for the model's physical fields (`opt.<name>` for its options) and, with
    `data`, the inputs listed in DATA_FIELDS (`data.<name>`)."""
    out = {f"opt.{n}": _digest(getattr(model.opt, n)) for n in _OPT_FIELDS if hasattr(model.opt, n)}
    out.update({n: _digest(getattr(model, n)) for n in _model_fields(model)})
    if data is not None:
        out.update({f"data.{n}": _digest(getattr(data, n)) for n in DATA_FIELDS if hasattr(data, n)})
    return out


def changed_fields(reference: dict[str, str], claimed: object) -> list[str]:
    """The fields whose digest in `claimed` (a worker's report: anything) differs from `reference`."""
    if not isinstance(claimed, dict):
        return []
    return sorted(k for k, v in reference.items() if k in claimed and claimed[k] != v)
