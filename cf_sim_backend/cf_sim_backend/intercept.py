"""Where a player first meets a rolling ball, running as rcssserver lets him (ROS-free).

rcssserver (14 and later) takes a dash in any direction off the body, at a share of its power
(``Params.dash_rate``: all of it straight ahead, 40% sideways, 70% straight back). A ball about
to roll by a metre or two to the side is met by dashing sideways at once; one 10 m off is met
sooner after a turn. For each cycle of the ball's path both are tried, by rcssserver's motion
(accelerate, cap the speed, move, decay), and the first point either reaches is the meeting.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cf_sim_backend.world import Params, norm_deg

DASH_POWER = 100.0
MAX_TURNS = 3  # turns looked at before a run: slowing down is what lets the next turn go further


@dataclass(frozen=True)
class Runner:
    """The player now: position, velocity (m/cycle) and the body's direction (degrees)."""

    x: float
    y: float
    vx: float
    vy: float
    body: float


@dataclass(frozen=True)
class Meeting:
    """Where and in how many cycles the ball is met, and the command that sets off for it:
    ``("dash", power, angle off the body)`` or ``("turn", angle)`` (the body's turn, not the moment)."""

    x: float
    y: float
    cycles: int
    command: tuple


def _dash_cycles(prm: Params, r: Runner, tx: float, ty: float, reach: float, angle: float, limit: int) -> int | None:
    """The first of ``limit`` cycles after which dashes at ``angle`` off the body (the body as it
    is) bring the player within ``reach`` of (tx, ty); None: not within the limit."""
    way = math.radians(r.body + angle)
    accel = DASH_POWER * prm.dash_power_rate * prm.effort_max * prm.dash_rate(angle)
    ax, ay = accel * math.cos(way), accel * math.sin(way)
    x, y, vx, vy = r.x, r.y, r.vx, r.vy
    for n in range(1, limit + 1):
        vx, vy = vx + ax, vy + ay
        speed = math.hypot(vx, vy)
        if speed > prm.player_speed_max:
            vx, vy = vx * prm.player_speed_max / speed, vy * prm.player_speed_max / speed
        x, y = x + vx, y + vy
        if math.hypot(tx - x, ty - y) <= reach:
            return n
        vx, vy = vx * prm.player_decay, vy * prm.player_decay
    return None


def turn_reach(prm: Params, speed: float) -> float:
    """The most degrees one turn turns the body at ``speed`` m/cycle (rcssserver's inertia)."""
    return prm.max_moment / (1.0 + prm.inertia_moment * speed)


def cycles_to(prm: Params, r: Runner, tx: float, ty: float, reach: float, limit: int) -> tuple[int, tuple] | None:
    """How soon the player can be within ``reach`` of (tx, ty), and the first command of the quicker
    way: dashing straight at it at whatever angle off the body, or turning to face it (up to
    MAX_TURNS turns), then dashing ahead. ``(0, ())``: within reach now."""
    if math.hypot(tx - r.x, ty - r.y) <= reach:
        return 0, ()
    angle = norm_deg(math.degrees(math.atan2(ty - r.y, tx - r.x)) - r.body)
    best = None
    n = _dash_cycles(prm, r, tx, ty, reach, angle, limit)
    if n is not None:
        best = (n, ("dash", DASH_POWER, angle))
    if abs(angle) > 1.0:
        # Turned (more than one turn when he is too fast to turn so far at once), he drifts a cycle
        # each time (his speed decays), then dashes straight ahead.
        x, y, vx, vy, left, turns = r.x, r.y, r.vx, r.vy, abs(angle), 0
        while left > 0.5 and turns < MAX_TURNS:
            left -= min(left, turn_reach(prm, math.hypot(vx, vy)))
            x, y, vx, vy, turns = x + vx, y + vy, vx * prm.player_decay, vy * prm.player_decay, turns + 1
        facing = math.degrees(math.atan2(ty - y, tx - x))
        later = limit - turns if best is None else min(limit - turns, best[0] - turns - 1)
        if left <= 0.5 and later >= 1:
            m = _dash_cycles(prm, Runner(x, y, vx, vy, facing), tx, ty, reach, 0.0, later)
            if m is not None:
                best = (m + turns, ("turn", angle))
    return best


def meeting(
    prm: Params, r: Runner, ball: tuple[float, float, float, float], reach: float, horizon: int
) -> Meeting | None:
    """The first point of the ball's path (x, y, vx, vy now; rolling as rcssserver rolls it) the
    player can be within ``reach`` of by the cycle the ball is there; None within ``horizon`` cycles."""
    x, y, vx, vy = ball
    for n in range(1, horizon + 1):
        x, y, vx, vy = x + vx, y + vy, vx * prm.ball_decay, vy * prm.ball_decay
        got = cycles_to(prm, r, x, y, reach, n)
        if got is not None:
            return Meeting(x, y, n, got[1])
    return None
