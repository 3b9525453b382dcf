"""Which side touched the ball last, as one player can tell (ROS-free).

The goalkeeper may not catch a ball a team-mate kicked last (rcssserver's back_pass: an indirect
free kick to the opponents in our penalty area, session 32), so he must know. The game does not
tell it; a player believes it from what he sees (only one side's men near the ball) and from what
his team-mates tell (the passes and clearances they announce as they kick).
"""

from __future__ import annotations

from cf_lang.ontology import Team, WorldState

from .situation import nearest_of_each_side, xy

TOUCH = 1.5  # m: a player this close to the ball may have touched it
FRESH = 1  # cycles: only players (and a ball) seen this lately count
CLEARLY = 0.2  # m: with both sides at the ball, the nearer side's man is this much nearer


class LastTouch:
    """The side that touched the ball last (None: not known)."""

    def __init__(self) -> None:
        self.team: Team | None = None

    def seen(self, state: WorldState) -> None:
        """Update from a perceived cycle: the side whose men alone are near the ball touched it, or,
        with both sides near it, the side of the clearly nearer man; else it stays as it was."""
        ball = state.ball
        if ball is None or ball.positioning is None or (ball.age or 0) > FRESH:
            return
        near = nearest_of_each_side(state, xy(ball.positioning), FRESH)
        nearest = {team: d for team, d in near.items() if d <= TOUCH}
        if len(nearest) == 1:
            self.team = next(iter(nearest))
        elif len(nearest) == 2:
            # Both sides at the ball: the nearer man, if clearly nearer, has it (a defender beside the
            # forward who kicked it had kept a shot "ours" and the keeper from catching it).
            ours, theirs = nearest[Team.OUR], nearest[Team.OPP]
            if abs(ours - theirs) >= CLEARLY:
                self.team = Team.OUR if ours < theirs else Team.OPP

    def played_by_mate(self) -> None:
        """A team-mate announced the pass or clearance he is kicking."""
        self.team = Team.OUR
