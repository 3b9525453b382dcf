"""Which side touched the ball last, as one player can tell (ROS-free).

The goalkeeper may not catch a ball a team-mate kicked last (rcssserver's back_pass: an indirect
free kick to the opponents in our penalty area, session 32), so he must know. The game does not
tell it; a player believes it from what he sees (only one side's men near the ball) and from what
his team-mates tell (the passes and clearances they announce as they kick). A ball rolling on its
course, as it was last seen, was touched by nobody, however near a man it passes.

A player who stood offside when a team-mate touched the ball may not play it until somebody
else touches it: rcssserver calls offside when he kicks or tackles it, or tries to within 2.5 m
of it (its ``OffsideRef``), and the embedded simulator does the same. Against Pyrus2D most of our
offsides were forwards beyond their line who went for a team-mate's dribble or a ball kicked into
space (docs/performance.md, session 59).
"""

from __future__ import annotations

import math

from cf_lang.ontology import PlayMode, Team, WorldState

from . import reach
from .situation import dist, nearest_of_each_side, offside_line, onside, play_mode, xy

TOUCH = 1.5  # m: a player this close to the ball may have touched it
FRESH = 1  # cycles: only players (and a ball) seen this lately count
CLEARLY = 0.2  # m: with both sides at the ball, the nearer side's man is this much nearer
COURSE = 3  # cycles: a ball last seen within this many cycles is followed along its course
OFF_COURSE = 0.4  # m/cycle (velocity) and m a cycle (position): a ball further off its course was played
OFFSIDE_MEMORY = 50  # cycles: a touch nobody was seen to follow lets an offside player play on after this
# (the rules keep him offside until the next touch, however late: a long ball rolls 40 cycles)


class LastTouch:
    """The side that touched the ball last (None: not known), and whether I stood offside then."""

    def __init__(self) -> None:
        self.team: Team | None = None
        self.course: tuple[int, tuple[float, float], tuple[float, float]] | None = None  # time, where, velocity
        self.offside_at: int | None = None  # the time of a team-mate's touch at which I stood offside

    def offside(self, time: int) -> bool:
        """Whether the rules forbid me the ball now: I stood offside at a team-mate's touch, and
        nobody has been seen to touch it since (for at most OFFSIDE_MEMORY cycles)."""
        return self.offside_at is not None and time - self.offside_at <= OFFSIDE_MEMORY

    def seen(self, state: WorldState) -> None:
        """Update from a perceived cycle: unless the ball rolls on its course, the side whose men alone
        are near it touched it, or, with both sides near it, the side of the clearly nearer man; else
        it stays as it was."""
        if play_mode(state) is not PlayMode.PLAY_ON:
            self.offside_at = None  # (any stoppage clears rcssserver's offside candidates)
        ball = state.ball
        if ball is None or ball.positioning is None:
            return
        if self.offside_at is not None and self.theirs_at(state, xy(ball.positioning)):
            # An opponent believed at the ball, none of ours, has had it, seen touching it or not:
            # far from the ball a forward saw too little to tell, and stood off their ball.
            self.offside_at = None
        if (ball.age or 0) > FRESH:
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
            self.touched(next(iter(nearest)), state, at, nearest.get(Team.OUR))
        elif len(nearest) == 2:
            # Both sides at the ball: the nearer man, if clearly nearer, has it (a defender beside the
            # forward who kicked it had kept a shot "ours" and the keeper from catching it).
            ours, theirs = nearest[Team.OUR], nearest[Team.OPP]
            if abs(ours - theirs) >= CLEARLY:
                self.touched(Team.OUR if ours < theirs else Team.OPP, state, at, ours)

    @staticmethod
    def theirs_at(state: WorldState, ball: tuple[float, float]) -> bool:
        """An opponent is believed within TOUCH of the ball, clearly nearer than any of us (however
        lately either was seen)."""
        near = nearest_of_each_side(state, ball)
        theirs, ours = near.get(Team.OPP, math.inf), near.get(Team.OUR, math.inf)
        if state.me and state.me.positioning:
            ours = min(ours, dist(xy(state.me.positioning), ball))
        return theirs <= TOUCH and theirs < ours - CLEARLY

    def touched(self, team: Team, state: WorldState, ball: tuple[float, float], mate: float | None) -> None:
        """``team`` touched the ball at ``ball``; ``mate``: how far the nearest team-mate (not me) was."""
        self.team = team
        self.offside_at = None
        me = xy(state.me.positioning) if state.me and state.me.positioning else None
        if team is not Team.OUR or me is None or mate is None or dist(me, ball) < mate:
            return  # theirs, or mine (nearer than any team-mate)
        if not onside(me[0], offside_line(state, ball)):
            self.offside_at = state.time

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

    def played_by_mate(self, offside_at: int | None = None) -> None:
        """A team-mate announced the pass or clearance he is kicking; ``offside_at``: the time it was
        heard, if I stood offside then."""
        self.team = Team.OUR
        self.offside_at = offside_at
