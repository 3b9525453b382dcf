"""Where a player is, from the landmarks it sees (ROS-free): position and head direction, with uncertainty.

Each seen flag i at known position F_i gives F_i = P + d_i * u(head + a_i), with d_i its distance,
a_i its direction relative to the head, u(angle) the unit vector. The difference of two flags
removes P: F_i - F_j = R(head) (d_i u(a_i) - d_j u(a_j)), so every pair gives the head direction;
their circular mean (weighted by the pair's baseline) is the estimate. Then each flag gives a position
and their mean is P; the spread of those gives the uncertainty. Server coordinates and degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Pose:
    x: float
    y: float
    head: float  # degrees, server convention
    sigma_xy: float
    sigma_head: float
    flags: int


def localise(flags: list[tuple[tuple[float, float], float, float]]) -> Pose | None:
    """The pose from (known position, distance, direction in degrees) of at least two landmarks."""
    if len(flags) < 2:
        return None
    sx = sy = wsum = 0.0
    headings = []
    for i in range(len(flags)):
        (fxi, fyi), di, ai = flags[i]
        for j in range(i + 1, len(flags)):
            (fxj, fyj), dj, aj = flags[j]
            world = math.atan2(fyi - fyj, fxi - fxj)
            rx = di * math.cos(math.radians(ai)) - dj * math.cos(math.radians(aj))
            ry = di * math.sin(math.radians(ai)) - dj * math.sin(math.radians(aj))
            baseline = math.hypot(fxi - fxj, fyi - fyj)
            if baseline < 1.0 or math.hypot(rx, ry) < 1e-6:
                continue
            head = world - math.atan2(ry, rx)
            weight = baseline / (1.0 + di + dj)  # long baselines to near flags are the most precise
            sx += weight * math.cos(head)
            sy += weight * math.sin(head)
            wsum += weight
            headings.append(head)
    if wsum == 0.0:
        return None
    head = math.atan2(sy, sx)
    spread = math.sqrt(max(0.0, -2.0 * math.log(max(1e-12, math.hypot(sx, sy) / wsum))))
    points = [
        (fx - d * math.cos(head + math.radians(a)), fy - d * math.sin(head + math.radians(a)), d)
        for (fx, fy), d, a in flags
    ]
    weights = [1.0 / (1.0 + d) for _, _, d in points]
    total = sum(weights)
    x = sum(w * p[0] for w, p in zip(weights, points, strict=True)) / total
    y = sum(w * p[1] for w, p in zip(weights, points, strict=True)) / total
    sigma = math.sqrt(
        sum(w * ((p[0] - x) ** 2 + (p[1] - y) ** 2) for w, p in zip(weights, points, strict=True)) / total
    )
    return Pose(x, y, math.degrees(head), max(sigma, 0.05), math.degrees(spread), len(flags))
