"""The soccer ontology: every class the Framework Language can name."""

from __future__ import annotations

from .actions import PLAYER_METHODS
from .base import LANGUAGE, ONTOLOGY, Concept, LineName, PlayMode, RegionName, Role, Team
from .objects import (
    FIELD,
    Ball,
    Flag,
    Game,
    Goal,
    Heard,
    Line,
    OffsideLine,
    Player,
    Referee,
    Region,
    SoccerField,
    WorldState,
)
from .positioning import AbsolutePositioning, RelativePositioning, Velocity

# Language name -> class. Action classes are reachable only through exec.
CLASSES: dict[str, type[Concept]] = {
    cls.__name__: cls
    for cls in (
        AbsolutePositioning,
        RelativePositioning,
        Velocity,
        SoccerField,
        Region,
        Flag,
        Goal,
        Line,
        OffsideLine,
        Ball,
        Player,
        Heard,
        Referee,
        Game,
        WorldState,
    )
}
CLASSES["Field"] = CLASSES.pop("SoccerField")
CLASSES.update({model.__name__: model for model, _ in PLAYER_METHODS.values()})

# Class name -> its methods (method name -> argument model).
METHODS: dict[str, dict[str, type[Concept]]] = {"Player": {m: model for m, (model, _) in PLAYER_METHODS.items()}}


def class_name(model: Concept | type[Concept]) -> str:
    """The language name of an ontology class."""
    cls = model if isinstance(model, type) else type(model)
    return "Field" if cls is SoccerField else cls.__name__


__all__ = [
    "CLASSES",
    "FIELD",
    "LANGUAGE",
    "METHODS",
    "ONTOLOGY",
    "PLAYER_METHODS",
    "AbsolutePositioning",
    "Ball",
    "Concept",
    "Flag",
    "Game",
    "Goal",
    "Heard",
    "Line",
    "LineName",
    "OffsideLine",
    "PlayMode",
    "Player",
    "Referee",
    "Region",
    "RegionName",
    "RelativePositioning",
    "Role",
    "SoccerField",
    "Team",
    "Velocity",
    "WorldState",
    "class_name",
]
