"""Joint couplings read from a URDF's <mimic> tags: a hand's follower joints move with their driver."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Mimic:
    """follower = multiplier * driver + offset (URDF <mimic>)."""

    follower: str
    driver: str
    multiplier: float
    offset: float


def read_mimics(urdf_path: Path) -> list[Mimic]:
    """Read every <mimic> tag of a URDF."""
    root = ET.parse(urdf_path).getroot()
    mimics = []
    for joint in root.iter("joint"):
        tag = joint.find("mimic")
        if tag is not None:
            mimics.append(
                Mimic(
                    follower=joint.attrib["name"],
                    driver=tag.attrib["joint"],
                    multiplier=float(tag.attrib.get("multiplier", 1.0)),
                    offset=float(tag.attrib.get("offset", 0.0)),
                )
            )
    return mimics
