"""Recorded rcssserver traces (`EPOCH DIR MESSAGE` per line) and localisation measured against them (ROS-free).

DIR is P>/P< (the player sent/received) or T>/T< (the trainer). The trainer's see_global is the
ground truth of the player's see in the same cycle.
"""

from __future__ import annotations

import gzip
import math
from dataclasses import dataclass, field
from pathlib import Path

from cf_sim_backend.rcss.belief import UNSURE, Belief
from cf_sim_backend.rcss.localise import localise
from cf_sim_backend.rcss.protocol import parse, read_see


def read_text(path: Path) -> str:
    """A trace's text (``.gz`` traces are read compressed)."""
    return gzip.decompress(path.read_bytes()).decode() if path.suffix == ".gz" else path.read_text()


def read_trace(path: Path) -> list[tuple[str, list]]:
    out = []
    for line in read_text(path).splitlines():
        _, direction, message = line.split(" ", 2)
        out.append((direction, parse(message)))
    return out


def _truth(msg: list, team: str) -> dict[str, list[float]]:
    """The player's and the ball's ground truth in a see_global: x y vx vy [body neck]."""
    out = {}
    for obj in msg[2:]:
        head = [str(v) for v in obj[0]]
        values = [float(v) for v in obj[1:] if isinstance(v, (int, float))]
        if head[0] == "b":
            out["ball"] = values
        elif head[0] == "p" and len(head) > 1 and head[1] == team:
            out["me"] = values
    return out


@dataclass
class BeliefErrors:
    """How far the belief was from the ground truth, cycle by cycle."""

    me: list[float] = field(default_factory=list)  # m, every cycle (seen or dead-reckoned) it claims to know
    unsure: int = 0  # cycles its own sigma said it did not know (e.g. moved by the server after a goal)
    me_seen: list[float] = field(default_factory=list)  # m, cycles with a see
    ball: list[float] = field(default_factory=list)  # m, cycles the ball was seen
    ball_velocity: list[float] = field(default_factory=list)  # m/cycle, cycles the ball was seen
    belief: Belief | None = None


def belief_errors(path: Path, team: str = "PyTest") -> BeliefErrors:
    """Replay what the traced player received and sent into a :class:`Belief`; compare it with see_global.

    The belief at the end of each cycle (after its sense_body and see) is compared with the trainer's
    ground truth of that cycle. Cycles before the first see are left out (nothing known yet).
    """
    belief, out = Belief(team), BeliefErrors()
    truth: dict[int, dict[str, list[float]]] = {}
    estimates: dict[int, tuple] = {}
    for direction, msg in read_trace(path):
        if direction == "T<" and str(msg[0]) == "see_global":
            truth[int(msg[1])] = _truth(msg, team)
        elif direction == "P<":
            kind = belief.update(msg)
            if kind in ("sense_body", "see") and belief.me.localised >= 0:
                b = belief.ball
                ball = (b.x, b.y, b.vx, b.vy) if b is not None and b.seen == belief.time else None
                me = belief.me
                estimates[belief.time] = (me.x, me.y, me.sigma, belief.see_time == belief.time, ball)
        elif direction == "P>":
            belief.sent(msg)
    for t, (x, y, sigma, seen, ball) in sorted(estimates.items()):
        true = truth.get(t, {})
        if "me" not in true:
            continue
        if sigma >= UNSURE:
            out.unsure += 1
            continue
        error = math.hypot(x - true["me"][0], y - true["me"][1])
        out.me.append(error)
        if seen:
            out.me_seen.append(error)
        if ball is not None and "ball" in true:
            out.ball.append(math.hypot(ball[0] - true["ball"][0], ball[1] - true["ball"][1]))
            out.ball_velocity.append(math.hypot(ball[2] - true["ball"][2], ball[3] - true["ball"][3]))
    out.belief = belief
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
