"""How fast a kick can send the ball, and the touch that lets the next kick send it faster (ROS-free).

rcssserver's kick adds to the ball's velocity an acceleration of at most
``kick_power_rate x 100``, less the further the ball lies off the body's front
and from its edge (``rate_at``), capped at ``ball_accel_max``. A ball at the edge of
the kickable area or beside the body leaves at two thirds of the speed or less,
which made half of our passes slow (session 42). A base team's answer, followed
here: one touch first that lays the ball where the second kick is strong,
counting the speed the touch leaves it with, which the second kick adds to.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_sim_backend.world import Params

CLEAR = 0.1  # m between the body's edge and a laid ball: no collision (which would stop it), noise allowed for
EDGE = 0.25  # m inside the kickable distance: a laid ball stays in reach despite the kick's noise
RINGS = 4  # distances from the body a laid ball is tried at
BEARINGS = 24  # directions round the body a laid ball is tried at


def rate_at(prm: Params, body: float, rx: float, ry: float) -> float:
    """The ball's acceleration per unit of kick power with the ball at (rx, ry) from my centre
    (rcssserver's formula; ``body`` in degrees)."""
    bearing = math.degrees(math.atan2(ry, rx)) - body
    dir_diff = abs((bearing + 180.0) % 360.0 - 180.0)
    gap = max(0.0, math.hypot(rx, ry) - prm.player_size - prm.ball_size)
    return prm.kick_power_rate * max(0.1, 1.0 - 0.25 * dir_diff / 180.0 - 0.25 * gap / prm.kickable_margin)


def most_accel(prm: Params, rate: float) -> float:
    """The most acceleration one kick gives the ball at this kick rate."""
    return min(100.0 * rate, prm.ball_accel_max)


def reach_along(prm: Params, ux: float, uy: float, vx: float, vy: float, most: float) -> float | None:
    """The fastest a kick of at most ``most`` sends a ball rolling at (vx, vy) along the unit (ux, uy);
    None: it rolls too fast across that way to be turned onto it."""
    along = ux * vx + uy * vy
    room = along * along - (vx * vx + vy * vy) + most * most
    if room < 0.0:
        return None
    return min(along + math.sqrt(room), prm.ball_speed_max)


@dataclass(frozen=True)
class Touch:
    """A first touch: the acceleration to give the ball, and the speed the kick after it reaches."""

    ax: float
    ay: float
    then: float


@dataclass(frozen=True)
class Kicker:
    """The kicker and the ball now: positions, velocities (m/cycle) and the body's direction (degrees)."""

    x: float
    y: float
    vx: float
    vy: float
    body: float
    bx: float
    by: float
    bvx: float
    bvy: float


def best_touch(
    prm: Params,
    k: Kicker,
    target: tuple[float, float],
    wanted: float,
    unsafe: list[tuple[float, float]] = (),
    safe_distance: float = 0.0,
) -> Touch | None:
    """The first of two touches after which the second sends the ball towards ``target`` fastest
    (up to ``wanted`` m/cycle; of those that reach it, the gentlest); None if no laid ball is any use.

    The laid ball is tried on rings round where I will be next cycle (I do not dash while I kick:
    I drift by my velocity), between the body's edge (plus CLEAR) and the kickable distance (less
    EDGE), on every side. A spot within ``safe_distance`` of a point of ``unsafe`` (where
    opponents will be) is not used.
    """
    rate = rate_at(prm, k.body, k.bx - k.x, k.by - k.y)
    most1 = most_accel(prm, rate)
    nx, ny = k.x + k.vx, k.y + k.vy
    inner = prm.player_size + prm.ball_size + CLEAR
    outer = prm.player_size + prm.ball_size + prm.kickable_margin - EDGE
    best: tuple[float, float, Touch] | None = None
    for i in range(RINGS):
        r = inner + (outer - inner) * i / max(1, RINGS - 1)
        for j in range(BEARINGS):
            angle = math.radians(k.body) + math.tau * j / BEARINGS
            lx, ly = nx + r * math.cos(angle), ny + r * math.sin(angle)
            ax, ay = lx - k.bx - k.bvx, ly - k.by - k.bvy
            push = math.hypot(ax, ay)
            if push > most1:
                continue
            if any(math.hypot(lx - ox, ly - oy) < safe_distance for ox, oy in unsafe):
                continue
            vx, vy = prm.ball_decay * (k.bvx + ax), prm.ball_decay * (k.bvy + ay)
            if math.hypot(k.bvx + ax, k.bvy + ay) > prm.ball_speed_max:
                continue
            way = math.atan2(target[1] - ly, target[0] - lx)
            most2 = most_accel(prm, rate_at(prm, k.body, lx - nx, ly - ny))
            then = reach_along(prm, math.cos(way), math.sin(way), vx, vy, most2)
            if then is None:
                continue
            score = (min(then, wanted), -push)
            if best is None or score > best[:2]:
                best = (*score, Touch(ax, ay, then))
    return None if best is None else best[2]
