"""The actions a player can execute: the methods of Player (paper, Fig. 5).

Each action is invoked as ``(exec Player <method> :playerNumber N :whichTeam T
<arguments>)``. Powers are 0..100 (percent of the maximum), angles radians
counter-clockwise (relative to the body unless the name says otherwise),
positions in the field frame.
"""

from __future__ import annotations

import math

from pydantic import Field, model_validator

from .base import Concept
from .objects import Ball, Flag, Goal, Player
from .positioning import AbsolutePositioning

Power = Field(ge=0.0, le=100.0, description="percent of the maximum")
Angle = Field(ge=-math.pi, le=math.pi, description="radians, counter-clockwise")


class Kick(Concept):
    """Kick the ball (it must be within the kickable distance)."""

    power: float = Power
    direction: float = Angle


class Shoot(Concept):
    """Kick at the opponents' goal; without a target, at its least covered point."""

    target: AbsolutePositioning | None = None
    power: float = Field(default=100.0, ge=0.0, le=100.0)


# m/cycle: a pass without :power leaves fast enough to reach its target with this pace left (slower
# passes are intercepted). The decision plans with it and the action kicks by it.
PASS_ARRIVAL_SPEED = 1.5


def pass_speed(dist: float, ball_decay: float) -> float:
    """The speed (m/cycle) a pass without :power leaves with to arrive ``dist`` metres on at PASS_ARRIVAL_SPEED.

    A rolling ball loses (1 - ball_decay) of its speed each cycle, about that share of the way in all.
    """
    return PASS_ARRIVAL_SPEED + dist * (1.0 - ball_decay)


class Pass(Concept):
    """Pass to a team-mate (``:to``) or to a point (``:target``): exactly one of them."""

    to: Player | None = None
    target: AbsolutePositioning | None = None
    power: float | None = Field(
        default=None, ge=0.0, le=100.0, description=f"None: arrives with {PASS_ARRIVAL_SPEED} m/cycle of pace left"
    )

    @model_validator(mode="after")
    def _one_target(self) -> Pass:
        if (self.to is None) == (self.target is None):
            raise ValueError("give exactly one of :to and :target")
        return self


class Dribble(Concept):
    """Run to a target keeping the ball close."""

    target: AbsolutePositioning
    speed: float = Field(
        default=60.0,
        ge=0.0,
        le=100.0,
        description="up to 70 the ball stays a step ahead; above, it runs ahead; an opponent near, it stays within reach",
    )


class HoldBall(Concept):
    """Keep the ball within reach, away from the opponents near, without going anywhere (until replaced)."""


class Intercept(Concept):
    """Run to where the ball can be reached first."""


class Tackle(Concept):
    """Try to take the ball from an opponent: it may fail, and the tackler stands still for a while after."""

    power: float = Power
    direction: float = Field(default=0.0, ge=-math.pi, le=math.pi, description="where the ball goes, from the body")


class Catch(Concept):
    """Goalkeeper only: catch the ball in this direction from the body, at most 90 degrees either side (rcssserver's)."""

    direction: float = Angle


class MoveTo(Concept):
    """Run to a target position."""

    target: AbsolutePositioning
    speed: float = Field(default=100.0, ge=0.0, le=100.0)


class Move(Concept):
    """Place the player (before kick-off or after a goal, own half only)."""

    target: AbsolutePositioning


class Dash(Concept):
    """Accelerate with a power in a direction relative to the body."""

    power: float = Field(ge=-100.0, le=100.0)
    direction: float = Field(default=0.0, ge=-math.pi, le=math.pi)


class Turn(Concept):
    """Turn the body by an angle."""

    angle: float = Angle


class TurnToObject(Concept):
    """Turn the body to face an object (a player, the ball, a flag or a goal)."""

    obj: Player | Ball | Flag | Goal


class TurnToDirection(Concept):
    """Turn the body to an absolute heading in the field frame."""

    direction: float = Angle


class TurnHead(Concept):
    """Point the head (camera) relative to the body."""

    angle: float = Field(ge=-math.pi / 2, le=math.pi / 2)


class Say(Concept):
    """Say a short message that nearby players hear."""

    message: str = Field(min_length=1, max_length=64)


# method name -> (argument model, service class that executes it)
PLAYER_METHODS: dict[str, tuple[type[Concept], str]] = {
    "kick": (Kick, "Kick"),
    "shoot": (Shoot, "Shoot"),
    "pass": (Pass, "Pass"),
    "dribble": (Dribble, "Dribble"),
    "holdBall": (HoldBall, "Dribble"),
    "intercept": (Intercept, "Intercept"),
    "tackle": (Tackle, "Tackle"),
    "catch": (Catch, "Catch"),
    "moveTo": (MoveTo, "MoveTo"),
    "move": (Move, "MoveTo"),
    "dash": (Dash, "Dash"),
    "turn": (Turn, "Turn"),
    "turnToObject": (TurnToObject, "Turn"),
    "turnToDirection": (TurnToDirection, "Turn"),
    "turnHead": (TurnHead, "HeadMovement"),
    "say": (Say, "Communication"),
}
