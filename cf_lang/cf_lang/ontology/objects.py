"""Static objects (field, regions, flags, goals, lines) and dynamic ones (ball, players, referee, game)."""

from __future__ import annotations

import math

from pydantic import Field

from .base import Concept, LineName, PlayMode, RegionName, Role, Team, player_number_field
from .positioning import AbsolutePositioning, RelativePositioning, Velocity

# ---- static objects ---------------------------------------------------------


class SoccerField(Concept):
    """The pitch's dimensions in metres (defaults: rcssserver's field)."""

    length: float = Field(default=105.0, gt=0)
    width: float = Field(default=68.0, gt=0)
    goal_width: float = Field(default=14.02, gt=0)
    penalty_area_length: float = Field(default=16.5, gt=0)
    penalty_area_width: float = Field(default=40.32, gt=0)
    goal_area_length: float = Field(default=5.5, gt=0)
    goal_area_width: float = Field(default=18.32, gt=0)
    centre_circle_radius: float = Field(default=9.15, gt=0)

    @property
    def half_length(self) -> float:
        return self.length / 2

    @property
    def half_width(self) -> float:
        return self.width / 2


# The standard field: the one place its dimensions are written (decision, simulator, report).
FIELD = SoccerField()


class Region(Concept):
    """A named rectangle of the field (the centre circle: its bounding box)."""

    KEY = ("name",)
    name: RegionName
    x_min: float | None = None
    x_max: float | None = None
    y_min: float | None = None
    y_max: float | None = None


class Flag(Concept):
    """A landmark with a known position, named as in rcssserver (e.g. "f c", "f p r t")."""

    KEY = ("name",)
    name: str = Field(min_length=1, max_length=32)
    positioning: AbsolutePositioning | None = None
    relative: RelativePositioning | None = None


class Goal(Concept):
    """A goal, named by the team that defends it."""

    KEY = ("whichTeam",)
    which_team: Team
    positioning: AbsolutePositioning | None = None
    relative: RelativePositioning | None = None
    width: float | None = Field(default=None, gt=0)


class Line(Concept):
    """A field line, as seen from the observer."""

    KEY = ("name",)
    name: LineName
    relative: RelativePositioning | None = None


class OffsideLine(Concept):
    """The x beyond which the named team's attackers are offside."""

    KEY = ("whichTeam",)
    which_team: Team
    x: float = Field(ge=-70.0, le=70.0)
    sigma_x: float | None = Field(default=None, ge=0.0)


# ---- dynamic objects --------------------------------------------------------


class Ball(Concept):
    """The ball: where it is (absolute and/or relative), how it moves, how old the estimate is."""

    positioning: AbsolutePositioning | None = None
    relative: RelativePositioning | None = None
    velocity: Velocity | None = None
    age: int | None = Field(default=None, ge=0, description="cycles since last seen")


class Player(Concept):
    """A player; the key is its shirt number and team."""

    KEY = ("playerNumber", "whichTeam")
    player_number: int | None = player_number_field(default=None)
    which_team: Team | None = None
    role: Role | None = None
    is_goalie: bool | None = None
    positioning: AbsolutePositioning | None = None
    relative: RelativePositioning | None = None
    velocity: Velocity | None = None
    head_angle: float | None = Field(default=None, ge=-math.pi, le=math.pi, description="relative to body")
    stamina: float | None = Field(default=None, ge=0.0, le=1.0, description="fraction of the maximum")
    top_speed: float | None = Field(default=None, gt=0.0, le=50.0, description="m/s that full dashes reach")
    age: int | None = Field(default=None, ge=0, description="cycles since last seen")


class Referee(Concept):
    """The referee's latest decision."""

    play_mode: PlayMode


class Game(Concept):
    """The one game: time in cycles (10 per second), play mode and score."""

    time: int = Field(default=0, ge=0)
    play_mode: PlayMode = PlayMode.BEFORE_KICK_OFF
    score_our: int = Field(default=0, ge=0)
    score_opp: int = Field(default=0, ge=0)
    half: int = Field(default=1, ge=1, le=4)


class Heard(Concept):
    """A team-mate's message this player heard (the back-end's ``say``: on rcssserver at most
    10 characters, heard within 50 m, one team-mate's message a cycle)."""

    player_number: int = player_number_field()
    message: str = Field(min_length=1, max_length=64)
    time: int = Field(ge=0, description="the game time it was heard")


class WorldState(Concept):
    """What one player perceives in one cycle: itself, the ball, the others, the game, what it heard."""

    time: int = Field(ge=0)
    me: Player | None = None
    ball: Ball | None = None
    players: tuple[Player, ...] = ()
    game: Game | None = None
    offside_lines: tuple[OffsideLine, ...] = ()
    heard: tuple[Heard, ...] = ()
