"""Recorded rcssserver traces (`EPOCH DIR MESSAGE` per line) and localisation measured against them (ROS-free).

DIR is P>/P< (the player sent/received) or T>/T< (the trainer). The trainer's see_global is the
ground truth of the player's see in the same cycle.
"""

from __future__ import annotations

import math
from pathlib import Path

from .localise import localise
from .rcss_protocol import parse, read_see


def read_trace(path: Path) -> list[tuple[str, list]]:
    out = []
    for line in path.read_text().splitlines():
        _, direction, message = line.split(" ", 2)
        out.append((direction, parse(message)))
    return out


def localisation_errors(path: Path) -> tuple[list[float], list[float]]:
    """Position errors (m) and head direction errors (degrees) of every localised see in a trace."""
    truth, sees = {}, []
    for direction, msg in read_trace(path):
        if direction == "T<" and str(msg[0]) == "see_global":
            for obj in msg[2:]:
                if str(obj[0][0]) == "p":
                    truth[int(msg[1])] = [float(v) for v in obj[1:] if isinstance(v, (int, float))]
        elif direction == "P<" and str(msg[0]) == "see":
            sees.append(read_see(msg))
    errors, head_errors = [], []
    for see in sees:
        pose, true = localise(see.flags()), truth.get(see.time)
        if pose is None or true is None:
            continue
        errors.append(math.hypot(pose.x - true[0], pose.y - true[1]))
        head_errors.append(abs((pose.head - (true[4] + true[5]) + 180) % 360 - 180))
    return errors, head_errors
