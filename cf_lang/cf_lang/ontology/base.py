"""The base of every ontology class and the closed vocabularies (enums)."""

from __future__ import annotations

from enum import StrEnum
from typing import ClassVar

from pydantic import AliasChoices, BaseModel, ConfigDict, Field
from pydantic.alias_generators import to_camel

LANGUAGE = "cf-lang"
ONTOLOGY = "robocup-soccer"


class Concept(BaseModel):
    """An ontology class. Attribute names in the language are camelCase."""

    model_config = ConfigDict(frozen=True, extra="forbid", alias_generator=to_camel, populate_by_name=True)

    KEY: ClassVar[tuple[str, ...]] = ()
    """Language names of the primary key (empty: there is only one instance)."""


class Team(StrEnum):
    """Teams are named relative to the speaker."""

    OUR = "our"
    OPP = "opp"


class Role(StrEnum):
    GOALKEEPER = "goalkeeper"
    DEFENDER = "defender"
    MIDFIELDER = "midfielder"
    FORWARD = "forward"


class PlayMode(StrEnum):
    """Play modes, relative to the speaker's team (rcssserver's l/r become our/opp)."""

    BEFORE_KICK_OFF = "before_kick_off"
    PLAY_ON = "play_on"
    KICK_OFF_OUR = "kick_off_our"
    KICK_OFF_OPP = "kick_off_opp"
    KICK_IN_OUR = "kick_in_our"
    KICK_IN_OPP = "kick_in_opp"
    CORNER_KICK_OUR = "corner_kick_our"
    CORNER_KICK_OPP = "corner_kick_opp"
    GOAL_KICK_OUR = "goal_kick_our"
    GOAL_KICK_OPP = "goal_kick_opp"
    FREE_KICK_OUR = "free_kick_our"
    FREE_KICK_OPP = "free_kick_opp"
    # A goal needs a second player's touch; the defenders may stand on their goal line (rcssserver:
    # after a back pass their goalkeeper caught, or a foul in the penalty area).
    INDIRECT_FREE_KICK_OUR = "indirect_free_kick_our"
    INDIRECT_FREE_KICK_OPP = "indirect_free_kick_opp"
    OFFSIDE_OUR = "offside_our"
    OFFSIDE_OPP = "offside_opp"
    GOAL_OUR = "goal_our"
    GOAL_OPP = "goal_opp"
    DROP_BALL = "drop_ball"
    HALF_TIME = "half_time"
    TIME_OVER = "time_over"


class RegionName(StrEnum):
    FIELD = "field"
    OUR_HALF = "ourHalf"
    OPP_HALF = "oppHalf"
    OUR_PENALTY_AREA = "ourPenaltyArea"
    OPP_PENALTY_AREA = "oppPenaltyArea"
    OUR_GOAL_AREA = "ourGoalArea"
    OPP_GOAL_AREA = "oppGoalArea"
    CENTRE_CIRCLE = "centreCircle"


class LineName(StrEnum):
    TOP = "top"
    BOTTOM = "bottom"
    OUR_GOAL_LINE = "ourGoalLine"
    OPP_GOAL_LINE = "oppGoalLine"
    HALFWAY = "halfway"


def player_number_field(**kwargs):
    """The player key: canonical ``:playerNumber``; ``:playerNum`` is accepted too."""
    return Field(
        ge=1,
        le=11,
        validation_alias=AliasChoices("playerNumber", "playerNum", "player_number"),
        serialization_alias="playerNumber",
        description="shirt number, 1..11",
        **kwargs,
    )
