"""One player's conversation with rcssserver (ROS-free): the belief, the skill in progress, the commands it sends.

The session turns server messages into the :class:`Belief` and, once per cycle (:meth:`PlayerSession.act`),
the current skill's step into rcssserver commands: at most one body command per cycle (the server
ignores extras), plus ``turn_neck``. Skills are the embedded simulator's (:mod:`skills`), run on
the belief, so the same Framework Language actions mean the same on both back-ends.
It also counts what a benchmark needs: cycles, body commands sent, and those the server executed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from cf_lang.errors import LanguageError
from cf_lang.ontology import FIELD
from cf_sim_backend.rcss.belief import HALF_VIEW, Belief
from cf_sim_backend.rcss.protocol import BODY_COMMANDS, parse
from cf_sim_backend.skills import Command, Skill
from cf_sim_backend.world import SAY_CHARACTERS, Side, norm_deg

_EXECUTED = ("kick", "dash", "turn", "move", "catch", "tackle")  # sense_body counters of body commands
_BALL_SKILLS = frozenset({"intercept", "shoot", "pass", "dribble", "holdBall", "kick", "catch", "tackle"})
SCAN_OFFSET = 40.0  # degrees the head looks off the ball: the view cone (120 at normal width) keeps it in sight
SCAN_MARGIN = 15.0  # degrees the ball stays inside the cone's edge, whatever the width
NARROW_WITHIN = 10.0  # m: a ball this close is watched every cycle (narrow view), not every other one
NORMAL_BEYOND = 13.0  # m: and back to normal width past this (a gap, so a ball about 10 m off does not flip it)
AROUND_WITHIN = 2.0  # m: a ball this close is seen all round (visible_distance 3 m): the head looks round the player
NECK_LIMIT = 90.0  # rcssserver's maxneckang (and -minneckang)
RECEIVE_SPEED = 0.8  # m/cycle: a ball rolling at least this fast goes where the belief says, unless touched
RECEIVE_AHEAD = 3  # cycles: while a ball we go for is further off than this, every other see looks upfield


def _n(value: float) -> str:
    """A number as the server reads it: at most 2 decimals, no exponent."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def rcss_command(cmd: Command) -> str | None:
    """A skill's command (embedded simulator's frame: y and angles mirrored) as rcssserver text, or None."""
    name, args = cmd[0], cmd[1:]
    if name == "dash":
        return f"(dash {_n(args[0])})" if len(args) < 2 or args[1] == 0 else f"(dash {_n(args[0])} {_n(-args[1])})"
    if name in ("turn", "turn_neck", "catch"):
        return f"({name} {_n(-args[0])})"
    if name == "kick":
        return f"(kick {_n(args[0])} {_n(-args[1])})"
    if name == "tackle":  # protocol 12+: the direction the ball goes, from the body
        return f"(tackle {_n(-args[0])})"
    if name == "move":  # own-half coordinates as for the left side: the server mirrors them for the right
        return f"(move {_n(args[0])} {_n(-args[1])})"
    if name == "say" and args:
        # (The ActionService refuses a say rcssserver would not carry; what gets here is trimmed to it.)
        text = "".join(c for c in str(args[0]) if c in SAY_CHARACTERS)[:10]
        return f'(say "{text}")' if text else None
    return None


@dataclass
class Acted:
    """What one cycle's act produced: the commands to send and the skill's status."""

    commands: list[str] = field(default_factory=list)
    status: str = "idle"  # idle | running | done | failed
    reason: str = ""
    name: str = ""  # the skill's
    cycles: int = 0


@dataclass
class PlayerSession:
    """A player's session. Parameters: team name, goalie, protocol version."""

    team: str
    goalie: bool = False
    version: int = 19
    belief: Belief = field(init=False)
    skill: Skill | None = None
    acted: int = -1  # the last server step (belief.steps) a body command went out in
    stats: dict[str, int] = field(
        default_factory=lambda: {"cycles": 0, "body_commands": 0, "executed": 0, "bad_messages": 0}
    )
    _counted: int = field(default=-1, init=False)
    # The last body command sent: (cycle, kind, the server's counter of that kind then, play mode),
    # checked at the next cycle's sense_body, so a benchmark can tell which commands did not run.
    _last_body: tuple[int, str, int, str] | None = field(default=None, init=False)
    unexecuted: list[str] = field(default_factory=list)  # the latest ten, for a benchmark's report
    _scan_see: int = field(default=-1, init=False)  # the see (belief.sees) the head's scan last swung at
    _scan_side: int = field(default=1, init=False)
    _scan_turn: int = field(default=0, init=False)  # counts sees: the phase of the look round
    _sweep: float | None = field(default=None, init=False)  # no ball believed: where the head's sweep has got to
    # The last server step (belief.steps) a turn_neck, a change_view went out in: one of each a step.
    _necked: int = field(default=-1, init=False)
    _viewed: int = field(default=-1, init=False)
    view: str = "normal"  # the view width the next see comes with (asked for; the server confirms in sense_body)
    to_say: str | None = None  # a say asked for, sent with the next cycle's commands (one a cycle)

    def __post_init__(self) -> None:
        self.belief = Belief(self.team, self.goalie)

    # ---- messages ---------------------------------------------------------------

    def hello(self) -> str:
        return f"(init {self.team} (version {self.version}){' (goalie)' if self.goalie else ''})"

    def reconnect(self, number: int) -> str:
        """Take player ``number`` back (after a relaunch); the server answers (reconnect SIDE MODE)."""
        self.belief.number = int(number)
        return f"(reconnect {self.team} {int(number)})"

    def receive(self, data: bytes | str) -> str:
        """Take one datagram; returns its kind ("see", "think", ...), or "bad" if it does not parse."""
        try:
            msg = parse(data)
        except (LanguageError, UnicodeDecodeError) as exc:
            self.stats["bad_messages"] += 1
            self.belief.note_error(f"unreadable message: {exc}")
            return "bad"
        if not isinstance(msg, list) or not msg:
            self.stats["bad_messages"] += 1
            return "bad"
        known = bool(self.belief.counters)
        before = sum(self.belief.counters.get(k, 0) for k in _EXECUTED)
        kind = self.belief.update(msg)
        if kind == "sense_body":
            # The server's counters of executed body commands (before the kick-off too, when time stands still).
            if known:
                self.stats["executed"] += max(0, sum(self.belief.counters.get(k, 0) for k in _EXECUTED) - before)
            if self.belief.time != self._counted:
                self._counted = self.belief.time
                self.stats["cycles"] += 1
            self._check_last_body()
        return kind

    def _check_last_body(self) -> None:
        """Count the last body command as unexecuted (by kind) if the next sense_body's counter did not move."""
        if self._last_body is None or self.belief.time <= self._last_body[0]:
            return
        sent_at, kind, before, mode = self._last_body
        self._last_body = None
        if kind in _EXECUTED and self.belief.counters.get(kind, before) <= before:
            key = f"unexecuted_{kind}"
            self.stats[key] = self.stats.get(key, 0) + 1
            self.unexecuted = [*self.unexecuted[-9:], f"{kind} sent at {sent_at} ({mode})"]

    def _look(self) -> list[str]:
        """This cycle's head and eye commands: the view width, then where the head points."""
        return self._view() + self._scan()

    def _view(self) -> list[str]:
        """The change_view for the ball's distance: narrow (a see every cycle, a 60 degree cone) near it.

        Near the ball every cycle counts: at normal width every other cycle's ball is a guess, and
        an opponent's dribble changes it unseen, so a contested ball looked kickable when it was
        not, or the other way round. Further off, the wider cone every other cycle sees more players.
        """
        b, me = self.belief, self.belief.me
        if self._viewed == b.steps:
            return []  # asked already this step
        self.view = me.view_width if me.view_width in HALF_VIEW else "normal"
        if me.localised < 0 or b.mode == "before_kick_off":
            return []
        d = math.hypot(b.ball.x - me.x, b.ball.y - me.y) if b.ball is not None else math.inf
        want = "narrow" if d <= NARROW_WITHIN else "normal" if d > NORMAL_BEYOND else self.view
        if want == self.view:
            return []
        self._viewed, self.view = b.steps, want
        return [f"(change_view {want})"]

    def _scan(self) -> list[str]:
        """The turn_neck that points the head for the next see: the view cone sweeps the field.

        Each see the head swings to the other side, SCAN_OFFSET off the ball, so the ball stays
        in view and every other see shows a different half of what is round it; with the ball
        within AROUND_WITHIN it looks round the player instead; with no ball believed, the head
        sweeps round a cone's width a see, the way the body turns. A pass is only as safe as the
        opponents the player has seen lately.
        """
        b, me = self.belief, self.belief.me
        if self._necked == b.steps or me.localised < 0:
            return []  # one turn_neck a step, and none before we know where we look
        new_see = b.sees != self._scan_see
        if new_see:
            self._scan_see, self._scan_side, self._scan_turn = b.sees, -self._scan_side, self._scan_turn + 1
        pending = b.pending.get("turn")
        turning = pending[2][0] if pending is not None and pending[1] == b.steps else 0.0
        body = norm_deg(me.body + turning)  # this cycle's turn moves the body the neck is on
        half = HALF_VIEW.get(self.view, 60.0)
        if b.ball is not None:
            self._sweep = None
        if b.ball is not None and math.hypot(b.ball.x - me.x, b.ball.y - me.y) <= AROUND_WITHIN:
            # The ball at our feet is seen wherever the head points: look left of the body, ahead
            # and right in turn, a cone's width apart. With the head on the ball, a narrow cone hid
            # the opponents closing in from the side, and the player on the ball ran into them.
            target = (self._scan_turn % 3 - 1) * 2.0 * half
        elif self._receiving():
            # Look where the ball will be played next while it rolls on its way: against HELIOS base
            # most passes went to an opponent the passer had not seen within 3 m of where he stood
            # (docs/performance.md, session 21). Every other see, as the ball was seen at the last.
            goal_x = -FIELD.length / 2 if b.side is Side.RIGHT else FIELD.length / 2
            target = norm_deg(math.degrees(math.atan2(-me.y, goal_x - me.x)) - body)
        elif b.ball is not None:
            to_ball = math.degrees(math.atan2(b.ball.y - me.y, b.ball.x - me.x))
            offset = min(SCAN_OFFSET, half - SCAN_MARGIN)
            target = norm_deg(to_ball + self._scan_side * offset - body)
        else:
            # Swinging from one limit of the neck to the other while the body turned a radian a
            # cycle pointed the head nearly at random: a defender 7 m from the ball looked for it
            # for 13 cycles while the goal he was to defend was scored (session 28).
            if self._sweep is None or new_see:
                start = me.head if self._sweep is None else self._sweep
                self._sweep = norm_deg(start + (-2.0 if turning < 0 else 2.0) * half)
            target = norm_deg(self._sweep - body)
        neck = max(-NECK_LIMIT, min(NECK_LIMIT, target))
        if b.ball is None:  # as far as the neck goes: the next cone's width on from there
            self._sweep = norm_deg(body + neck)
        turn = neck - me.neck
        if abs(turn) < 1.0:
            return []
        self._necked = b.steps
        return [f"(turn_neck {_n(turn)})"]

    def _receiving(self) -> bool:
        """Whether we go for a rolling ball, seen at the last see, still RECEIVE_AHEAD cycles or more away.

        Never the goalkeeper: the ball he goes for may be a shot, and he catches only what he sees.
        """
        b, me = self.belief, self.belief.me
        if self.goalie or self.skill is None or self.skill.name != "intercept":
            return False
        if b.ball is None or b.ball.seen != b.see_time:
            return False
        speed = math.hypot(b.ball.vx, b.ball.vy)
        return speed >= RECEIVE_SPEED and math.hypot(b.ball.x - me.x, b.ball.y - me.y) >= RECEIVE_AHEAD * speed

    @property
    def ready(self) -> bool:
        """Whether the server has told us who we are."""
        return self.belief.side is not None and self.belief.number > 0

    # ---- acting -----------------------------------------------------------------

    def start(self, skill: Skill | None) -> None:
        """Carry out ``skill`` from the next :meth:`act` on (replacing the current one)."""
        self.skill = skill

    def say(self, text: str) -> None:
        """Say ``text`` with the next commands (a later say before then replaces it)."""
        self.to_say = text

    def act(self) -> Acted:
        """This cycle's commands: the current skill's step, at most one body command, once per cycle,
        and the say asked for."""
        acted = self._act()
        if self.to_say is not None and self.ready and self.belief.mode != "time_over":
            text = rcss_command(("say", self.to_say))
            if text is not None:
                acted.commands.append(text)
            self.to_say = None
        return acted

    def _act(self) -> Acted:
        b = self.belief
        if not self.ready or b.mode == "time_over":
            return Acted()  # (after time over the server executes nothing: a command then is only noise)
        if self.skill is None or self.acted == b.steps:
            return Acted(self._look())
        if b.ball is None and self.skill.name in _BALL_SKILLS:
            # The last see showed that the ball is not where we believed: do not play a ball we
            # cannot place (the decision, told, looks for it).
            skill, self.skill = self.skill, None
            return Acted([], "failed", "the ball is out of sight", skill.name, skill.cycles)
        world = b.world()
        me = world.player(b.side, b.number)
        if me.frozen > 0:
            return Acted(self._look())  # a tackle holds us: the server would ignore any body command
        step = self.skill.step(world, me)
        out, body_sent = [], False
        for cmd in step.commands:
            text = rcss_command(cmd)
            if text is None:
                continue
            if cmd[0] in BODY_COMMANDS:
                if body_sent:
                    continue  # the server would ignore it: keep the first
                body_sent = True
            b.sent(parse(text))  # dead reckoning until the next see
            out.append(text)
            if cmd[0] in _EXECUTED and cmd[0] in b.counters:
                self._last_body = (b.time, cmd[0], b.counters[cmd[0]], b.server_mode)
        if body_sent:
            self.acted = b.steps
            self.stats["body_commands"] += 1
        out += self._view()
        if any(text.startswith("(turn_neck") for text in out):
            self._necked = b.steps
        else:
            out += self._scan()
        skill = self.skill
        if step.status != "running":
            self.skill = None
        return Acted(out, step.status, step.reason, skill.name, skill.cycles)
