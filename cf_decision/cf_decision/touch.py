"""Which side touched the ball last, as one player can tell (ROS-free).

The goalkeeper may not catch a ball a team-mate kicked last (rcssserver's back_pass: an indirect
free kick to the opponents in our penalty area, session 32), so he must know. The game does not
tell it; a player believes it from what he sees (only one side's men near the ball) and from what
his team-mates tell (the passes and clearances they announce as they kick). A ball rolling on its
course, as it was last seen, was touched by nobody, however near a man it passes.
"""

from __future__ import annotations

import math

from cf_lang.ontology import Team, WorldState

from . import reach
from .situation import nearest_of_each_side, xy

TOUCH = 1.5  # m: a player this close to the ball may have touched it
FRESH = 1  # cycles: only players (and a ball) seen this lately count
CLEARLY = 0.2  # m: with both sides at the ball, the nearer side's man is this much nearer
COURSE = 3  # cycles: a ball last seen within this many cycles is followed along its course
OFF_COURSE = 0.4  # m/cycle (velocity) and m a cycle (position): a ball further off its course was played


class LastTouch:
    """The side that touched the ball last (None: not known)."""

    def __init__(self) -> None:
        self.team: Team | None = None
        self.course: tuple[int, tuple[float, float], tuple[float, float]] | None = None  # time, where, velocity

    def seen(self, state: WorldState) -> None:
        """Update from a perceived cycle: unless the ball rolls on its course, the side whose men alone
        are near it touched it, or, with both sides near it, the side of the clearly nearer man; else
        it stays as it was."""
        ball = state.ball
        if ball is None or ball.positioning is None or (ball.age or 0) > FRESH:
            return
        at, velocity = xy(ball.positioning), reach.per_cycle(ball.velocity)
        on_course = self.on_course(state.time, at, velocity)
        self.course = (state.time, at, velocity) if ball.velocity is not None else None
        if on_course:
            # A shot that passed a defender a metre off had been taken for his, and the keeper cleared
            # it instead of catching it (22 times in 21 matches against HELIOS base, session 53).
            return
        near = nearest_of_each_side(state, at, FRESH)
        nearest = {team: d for team, d in near.items() if d <= TOUCH}
        if len(nearest) == 1:
            self.team = next(iter(nearest))
        elif len(nearest) == 2:
            # Both sides at the ball: the nearer man, if clearly nearer, has it (a defender beside the
            # forward who kicked it had kept a shot "ours" and the keeper from catching it).
            ours, theirs = nearest[Team.OUR], nearest[Team.OPP]
            if abs(ours - theirs) >= CLEARLY:
                self.team = Team.OUR if ours < theirs else Team.OPP

    def on_course(self, time: int, at: tuple[float, float], velocity: tuple[float, float]) -> bool:
        """Whether the ball, seen at ``time``, is where and as fast as rolling on from its last
        sighting (within COURSE cycles) would have it: nobody touched it."""
        if self.course is None or not 0 < time - self.course[0] <= COURSE or math.hypot(*velocity) == 0.0:
            return False
        then, where, was = self.course
        cycles = time - then
        rolled = reach.ball_path(where, was, cycles)[-1]
        slowed = (was[0] * reach.BALL_DECAY**cycles, was[1] * reach.BALL_DECAY**cycles)
        return (
            math.dist(at, rolled) <= OFF_COURSE * cycles
            and math.dist(velocity, slowed) <= OFF_COURSE
            and math.hypot(*was) > OFF_COURSE  # a ball at rest near a man may be at his feet
        )

    def played_by_mate(self) -> None:
        """A team-mate announced the pass or clearance he is kicking."""
        self.team = Team.OUR
