"""The rcssserver adapter's belief and session against the recorded server traces and crafted messages.

Traces (test/data/rcss/): rcssserver 19, one player and a trainer with (eye on); see_global gives the
ground truth of each cycle. The 1000-cycle one is in synch mode with goals, kick-ins and drop balls.
"""

from __future__ import annotations

import math
import statistics
from pathlib import Path

import pytest

from cf_lang.ontology import PlayMode, Team
from cf_lang.ontology import actions as act
from cf_lang.ontology.positioning import AbsolutePositioning
from cf_sim_backend.embedded.rcg import RCSS_PLAYMODES
from cf_sim_backend.rcss.belief import PLAYER_MEMORY, SIM_MODES, UNSURE, Belief, Track, sim_mode, world_state
from cf_sim_backend.rcss.protocol import BODY_COMMANDS, parse, well_formed
from cf_sim_backend.rcss.session import PlayerSession, rcss_command
from cf_sim_backend.rcss.trace import belief_errors, read_trace
from cf_sim_backend.skills import Intercept, KickTo, MoveTo, Skill, SkillError, skill_for
from cf_sim_backend.world import Side, norm_deg

DATA = Path(__file__).parent / "data" / "rcss"
TRACES = ["player-trainer-150cycles.log", "player-trainer-opponents-1000cycles-synch.log.gz"]
SYNCH = DATA / TRACES[1]

BODY = BODY_COMMANDS


# ---- every message, and the checker itself --------------------------------------


@pytest.mark.parametrize("trace", TRACES)
def test_every_message_of_both_traces_parses(trace):
    messages = read_trace(DATA / trace)
    assert len(messages) > 600
    kinds = {str(m[0]) for _, m in messages}
    assert {"init", "server_param", "player_param", "player_type", "sense_body", "see", "hear"} <= kinds


def test_the_command_checker_accepts_what_the_real_client_sent_and_rejects_nonsense():
    sent = [msg for direction, msg in read_trace(SYNCH) if direction == "P>"]
    texts = [line.split(" ", 2)[2] for line in _lines(SYNCH) if line.split(" ", 2)[1] == "P>"]
    assert len(texts) == len(sent) > 1000 and all(well_formed(t) for t in texts)
    for bad in ("(dash 200)", "(kick 50)", "(turn abc)", "(dash 1e5)", '(say "too long a message")', "(fly 3)"):
        assert not well_formed(bad), bad


def _lines(path: Path) -> list[str]:
    from cf_sim_backend.rcss.trace import read_text

    return read_text(path).splitlines()


# ---- the belief against the ground truth ------------------------------------------


@pytest.mark.parametrize("trace", TRACES)
def test_belief_follows_the_ground_truth_every_cycle(trace):
    errors = belief_errors(DATA / trace)
    me, ball = sorted(errors.me), sorted(errors.ball)
    assert len(me) > 140 and len(ball) > 40
    # Stated errors (every cycle: localised from flags, or carried on by the sensed speed and our turns).
    assert statistics.mean(me) < 0.15 and me[int(0.95 * len(me))] < 0.3 and me[-1] < 1.0
    assert statistics.mean(ball) < 0.5 and ball[int(0.95 * len(ball))] < 1.0
    assert statistics.mean(errors.ball_velocity) < 0.1  # m/cycle, from the see's distance/direction change
    assert errors.unsure <= 0.02 * len(me)  # cycles after the server moved us, until the next see


def test_belief_follows_play_modes_and_the_score():
    belief = belief_errors(SYNCH).belief
    assert belief.side is Side.LEFT and belief.number == 1
    assert belief.score == {Side.LEFT: 2, Side.RIGHT: 0} and belief.mode == "play_on"
    assert belief.server["ball_decay"] == 0.94 and len(belief.player_types) == 18
    assert belief.params().kickable_distance == pytest.approx(1.005)  # see the reach test


@pytest.mark.parametrize(
    ("server", "ours"),
    [
        ("goal_l_3", "goal_l"),
        ("kick_in_r", "kick_in_r"),
        ("free_kick_fault_l", "free_kick_r"),
        ("back_pass_r", "indirect_free_kick_l"),
        ("indirect_free_kick_l", "indirect_free_kick_l"),
        ("foul_charge_l", "free_kick_r"),  # (indirect in the penalty area: the server says so next)
        ("time_up", "time_over"),
        ("play_on", "play_on"),
    ],
)
def test_server_play_modes_map_to_the_simulators(server, ours):
    assert sim_mode(server) == ours


# Every play mode rcssserver 19 has, and the referee's other messages (goals with the score, cards).
REFEREE = [
    *RCSS_PLAYMODES,
    "goal_l_1",
    "goal_r_12",
    "yellow_card_l_3",
    "yellow_card_r_2",
    "red_card_l_11",
    "time_up",
    "time_up_without_a_team",
    "time_extended",
    "half_time",
    "foul_l",
    "goalie_catch_ball_r",
    "penalty_onfield_l",
    "penalty_foul_r",
    "penalty_winner_l",
    "penalty_draw",
    "something_a_newer_server_says",
]


@pytest.mark.parametrize("said", REFEREE)
def test_every_referee_message_is_read_and_none_is_fatal(said):
    """A card must not end the adapter (it ended all eleven at cycle 4958 of a match against HELIOS)."""
    b = _belief()
    b.update(parse("(hear 0 referee play_on)"))
    b.update(parse(f"(hear 10 referee {said})"))
    assert b.mode in SIM_MODES
    state = world_state(b)  # what the perception sends: its play mode must be one the language knows
    assert state.game.play_mode in set(PlayMode)
    if said.startswith(("yellow_card", "red_card")):
        assert b.mode == "play_on" and b.referee_notes[-1] == said
    if said == "something_a_newer_server_says":
        assert b.mode == "play_on" and "unknown referee message" in b.errors[-1]


def _belief(side: str = "l", number: int = 7) -> Belief:
    b = Belief("CF")
    b.update(parse(f"(init {side} {number} before_kick_off)"))
    return b


SEE_CENTRE = "((f c) 10 0) ((f c t) 35.44 -73.6) ((f c b) 35.44 73.6)"  # at (-10, 0), facing +x


def test_a_ball_not_seen_where_it_would_be_seen_is_no_longer_believed():
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 10 {SEE_CENTRE} ((b) 0.9 0 0 0))"))  # at our feet
    assert b.ball is not None and b.ball.x == pytest.approx(-9.1, abs=0.1)
    b.update(parse("(sense_body 11 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 11 {SEE_CENTRE})"))  # an opponent took it: the server would show it within 3 m
    assert b.ball is None
    session = PlayerSession("CF")
    session.belief = b
    session.skill = skill_for("intercept", act.Intercept(), Side.LEFT, b.world(), b.world().player(Side.LEFT, 7))
    acted = session.act()
    assert acted.commands == [] and acted.status == "failed" and "out of sight" in acted.reason
    # Far away behind our back a ball is not expected in the see: the estimate stays.
    b.update(parse(f"(see 12 {SEE_CENTRE} ((b) 20 179 0 0))"))
    b.update(parse(f"(see 13 {SEE_CENTRE})"))
    assert b.ball is not None and b.ball.x == pytest.approx(-30.0, abs=0.5)


@pytest.mark.parametrize(
    "mode, where",
    [
        ("kick_in_r", (20.0, 34.0)),
        ("goal_kick_l", (-47.0, 9.16)),
        ("corner_kick_l", (51.5, 33.0)),
        ("kick_off_l", (0.0, 0.0)),  # believed in the goal it went into
    ],
)
def test_the_ball_is_believed_where_the_referee_places_it_for_a_set_piece(mode, where):
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    b.ball = Track(20.0, 36.0, 0.5, 0.5, 0.2, 10) if mode == "kick_in_r" else Track(-53.0, 5.0, 0.0, 0.0, 0.2, 10)
    if mode == "corner_kick_l":
        b.ball = Track(53.0, 20.0, 1.0, 0.0, 0.2, 10)
    if mode == "kick_off_l":
        b.ball = Track(-58.0, -3.0, -0.4, 0.1, 0.2, 10)
    b.update(parse(f"(hear 11 referee {mode})"))
    assert (b.ball.x, b.ball.y) == pytest.approx(where) and (b.ball.vx, b.ball.vy) == (0.0, 0.0)


def test_players_are_tracked_by_team_and_number_with_ages_then_forgotten():
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high normal) (stamina 8000 1 130600) (speed 0 0) (head_angle 0))"))
    b.update(
        parse(f'(see 10 {SEE_CENTRE} ((p "CF" 3) 5 0 0 0 90 0) ((p "Opp" 9 goalie) 20 0) ((p "Opp") 40 10) ((P) 1 90))')
    )
    assert b.opponent == "Opp" and set(b.players) == {("CF", 3), ("Opp", 9)}
    assert b.players[("CF", 3)].x == pytest.approx(-5.0, abs=0.1) and b.players[("Opp", 9)].goalie
    state = world_state(b)
    mate = next(p for p in state.players if p.player_number == 3)
    assert mate.which_team is Team.OUR and mate.age == 0 and mate.positioning.x == pytest.approx(-5.0, abs=0.1)
    assert mate.positioning.yaw == pytest.approx(-math.pi / 2, abs=0.05)  # body 90 deg clockwise = -y in our frame
    anonymous = [p for p in state.players if p.player_number is None]
    assert {p.which_team for p in anonymous} == {Team.OPP, None}  # far: team only; very near: nothing
    for t in range(11, 11 + PLAYER_MEMORY):
        b.update(parse(f"(sense_body {t} (speed 0 0) (head_angle 0))"))
    assert world_state(b).players[0].age == PLAYER_MEMORY and not world_state(b).players[0].positioning.sigma_x < 5
    b.update(parse(f"(sense_body {11 + PLAYER_MEMORY} (speed 0 0) (head_angle 0))"))
    assert not b.players  # forgotten


def test_a_player_out_of_sight_runs_on_as_he_was_last_seen_running_a_tenth_slower_each_cycle():
    """The see shows a player's velocity after the cycle's decay (0.4): 0.4 m/cycle closing is a 1 m step.

    Kept where he was last seen, HELIOS base's men near the ball were more than 3 m off after 7 cycles
    in 61% of cases on six game logs' truth (tools/rcss_run_on.py), 18% run on so.
    """
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high normal) (stamina 8000 1 130600) (speed 0 0) (head_angle 0))"))
    sightings = '((p "Opp" 9) 10 0 -0.4 0 0 0) ((p "Opp" 4) 5 0 0 0 0 0) ((p "Opp" 7) 5 0 -3 0 0 0)'
    b.update(parse(f"(see 10 {SEE_CENTRE} {sightings})"))
    assert b.players[("Opp", 9)].x == pytest.approx(0.0, abs=0.1)  # I stand at (-10, 0), facing +x
    for t in range(11, 14):
        b.update(parse(f"(sense_body {t} (speed 0 0) (head_angle 0))"))
    assert b.players[("Opp", 9)].x == pytest.approx(-(1.0 + 0.9 + 0.81), abs=0.15)
    assert b.players[("Opp", 4)].x == pytest.approx(-5.0, abs=0.1)  # seen standing: stays
    assert b.players[("Opp", 7)].x == pytest.approx(-5.0 - 1.2 * 3, abs=0.1)  # no faster than any type runs


def test_the_top_speeds_of_me_and_my_team_mates_follow_their_types_and_the_opponents_stay_unknown():
    """The server tells a team-mate's new type and an opponent's change only (rcssserver 19's texts)."""
    b = _belief(number=7)
    b.update(
        parse("(player_type (id 0)(player_speed_max 1.05)(player_decay 0.4)(dash_power_rate 0.006)(effort_max 1))")
    )
    b.update(
        parse(
            "(player_type (id 4)(player_speed_max 1.05)(player_decay 0.373568)(dash_power_rate 0.0048878)"
            "(effort_max 0.988757))"
        )
    )
    b.update(parse("(player_type (id 9)(player_speed_max 1.05)(player_decay 0.5)(dash_power_rate 0.006))"))
    for msg in ("(change_player_type 7 4)", "(change_player_type 3 9)", "(change_player_type 5)"):
        b.update(parse(msg))
    b.update(parse("(sense_body 10 (view_mode high normal) (stamina 8000 1 130600) (speed 0 0) (head_angle 0))"))
    b.update(parse(f'(see 10 {SEE_CENTRE} ((p "CF" 3) 5 0 0 0 90 0) ((p "CF" 8) 6 20) ((p "Opp" 5) 20 0))'))
    state = world_state(b)
    speeds = {(p.which_team, p.player_number): p.top_speed for p in state.players}
    assert state.me.top_speed == pytest.approx(7.715, abs=0.001)  # 0.489 m/cycle a dash, 37% of it lost a cycle
    assert speeds[(Team.OUR, 3)] == pytest.approx(10.5)  # 1.2 m/cycle at full dashes, capped at 1.05
    assert speeds[(Team.OUR, 8)] == pytest.approx(10.0)  # never changed: the default type
    assert speeds[(Team.OPP, 5)] is None  # changed, but to what nobody says
    assert b.type_id == 4 and b.params().top_speed == pytest.approx(0.7715, abs=0.0001)


def test_a_player_seen_without_a_number_is_the_known_player_nearest_him():
    """Outside the view cone a close player is just (P): he is who we last saw near there."""
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high narrow) (speed 0 0) (head_angle 0))"))
    b.update(parse(f'(see 10 {SEE_CENTRE} ((p "Opp" 6) 4 -20 0 0 0 0) ((p "CF" 8) 6 20 0 0 0 0))'))
    for t in (11, 12, 13):
        b.update(parse(f"(sense_body {t} (view_mode high narrow) (speed 0 0) (head_angle 0))"))
    # In 3 cycles he ran 4 m round to our left side, 1 m off, 100 degrees off our head: no team, no number.
    b.update(parse(f'(see 13 {SEE_CENTRE} ((P) 1 -100) ((p "Opp") 45 0))'))
    opp = b.players[("Opp", 6)]
    assert (opp.x, opp.y, opp.seen) == pytest.approx((-10.17, -0.98, 13), abs=0.05)
    assert b.players[("CF", 8)].seen == 10  # the team-mate was further from the sighting
    assert [team for team, _ in b.anonymous] == ["Opp"]  # 45 m off: near no known player, stays anonymous
    near = [p for p in world_state(b).players if p.relative.distance < 2.0]
    assert [(p.which_team, p.player_number, p.age) for p in near] == [(Team.OPP, 6, 0)]


def test_a_right_side_player_sees_the_field_from_its_own_goal():
    b = _belief("r", 2)
    b.update(parse("(sense_body 0 (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 0 {SEE_CENTRE} ((b) 10 0))"))  # server: at (-10, 0) facing +x, ball at the centre
    state = world_state(b)
    me = state.me.positioning
    assert me.x == pytest.approx(10.0, abs=0.1) and me.y == pytest.approx(0.0, abs=0.1)  # attacking -x: own frame flips
    assert abs(me.yaw) == pytest.approx(math.pi, abs=0.02)
    assert state.ball.positioning.x == pytest.approx(0.0, abs=0.6) and state.ball.age == 0
    b.update(parse("(hear 0 referee kick_off_r)"))
    assert world_state(b).game.play_mode is PlayMode.KICK_OFF_OUR


def test_ball_rolls_on_with_decay_and_its_age_grows_while_not_seen():
    b = _belief()
    b.update(parse("(sense_body 5 (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 5 {SEE_CENTRE} ((b) 5 0 1 0))"))  # 5 m ahead, moving away at 1 m/cycle
    assert b.ball.vx == pytest.approx(1.0, abs=0.05)
    b.update(parse("(sense_body 6 (speed 0 0) (head_angle 0))"))
    ball = world_state(b).ball
    assert ball.age == 1 and ball.positioning.x == pytest.approx(-4.0, abs=0.1)
    assert ball.velocity.vx == pytest.approx(9.4, abs=0.5)  # m/s after one cycle's decay


def test_a_goal_makes_the_pose_unknown_until_the_next_see():
    b = _belief()
    b.update(parse("(sense_body 5 (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 5 {SEE_CENTRE})"))
    assert b.me.sigma < 1.0
    b.update(parse("(hear 5 referee goal_l_1)"))
    assert b.me.sigma >= UNSURE and b.score[Side.LEFT] == 1
    b.update(parse(f"(see 5 {SEE_CENTRE})"))
    assert b.me.sigma < 1.0


def test_the_skills_world_gives_a_man_whose_body_was_not_seen_the_way_he_runs():
    """The foul check of a tackle reads an opponent's body (a man between the tackler and the ball,
    facing its way, is fouled); a see tells it only for men near and in the view cone."""
    b = _belief()
    b.players[("HELIOS", 9)] = Track(5.0, 2.0, 0.6, 0.8, 1.0, 0)  # server frame: running down and right
    b.players[("HELIOS", 8)] = Track(9.0, 2.0, 0.6, 0.8, 1.0, 0, body=30.0)
    w = b.world()
    assert w.player(Side.RIGHT, 9).body == pytest.approx(math.degrees(math.atan2(-0.8, 0.6)))  # y mirrored
    assert w.player(Side.RIGHT, 8).body == pytest.approx(-30.0)  # seen: as seen


def _pass_direction(b: Belief, true_velocity: tuple[float, float], to: tuple[float, float]) -> float:
    """Where (degrees, server frame) the pass skill's kick really sends the ball, given its true velocity."""
    session = PlayerSession("CF")
    session.belief = b
    b.me.localised = b.see_time = b.time
    world = b.world()
    session.start(KickTo("pass", to[0], -to[1], None, approach=False))  # the skills' frame: y mirrored
    kick = next(parse(c) for c in session.act().commands if c.startswith("(kick"))
    ax, ay = b._kick_accel(float(kick[1]), float(kick[2]))
    vx, vy = true_velocity[0] + ax, true_velocity[1] + ay
    assert world.ball is not None
    return math.degrees(math.atan2(vy, vx))


def test_a_ball_that_rolls_into_our_body_bounces_off_it_and_the_pass_still_goes_where_it_aims():
    """rcssserver: a ball that ends a cycle overlapping a player is put against him, its velocity
    times -0.1. A kick that took out the old velocity sent passes off by up to 120 degrees."""
    b = _belief()
    b.update(parse("(sense_body 10 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 10 {SEE_CENTRE} ((b) 1.2 0 -1 0))"))  # 1.2 m ahead, rolling at us at 1 m/cycle
    b.update(parse("(sense_body 11 (view_mode high normal) (speed 0 0) (head_angle 0))"))  # no see this cycle
    assert math.hypot(b.ball.x + 10.0, b.ball.y) == pytest.approx(0.385, abs=0.01)  # against us, not through us
    assert (b.ball.vx, b.ball.vy) == pytest.approx((0.094, 0.0), abs=0.01)
    aim = math.degrees(math.atan2(-15.0, 0.0))  # a team-mate 15 m to our left (server frame: -y)
    assert abs(_pass_direction(b, (0.094, 0.0), (-10.0, -15.0)) - aim) < 5.0

    # We ran into it: the sense_body says so (collision (ball)); the see outside the view cone gives
    # no velocity. Our own speed was turned round too: the step we made was forwards.
    b = _belief()
    b.update(parse("(sense_body 20 (view_mode high narrow) (speed 0 0) (head_angle 0))"))
    b.update(parse(f"(see 20 {SEE_CENTRE} ((b) 1.6 -70))"))
    b.ball.vx, b.ball.vy = 0.0, -0.6  # rolling away across our way, as believed: 1.1 m off after one cycle
    b.update(parse("(sense_body 21 (view_mode high narrow) (speed 0.03 180) (head_angle 0) (collision (ball)))"))
    assert b.me.x == pytest.approx(-10.0 + 0.75, abs=0.05)  # 0.03 after decay (0.4) and the bounce (-0.1)
    assert math.hypot(b.ball.x - b.me.x, b.ball.y - b.me.y) == pytest.approx(0.385, abs=0.01)
    b.update(parse(f"(see 21 {SEE_CENTRE} ((b) 0.4 -70))"))  # 70 degrees off: outside the narrow cone
    assert (b.ball.vx, b.ball.vy) == pytest.approx((0.0, 0.056), abs=0.01)
    assert abs(_pass_direction(b, (0.0, 0.056), (0.0, 0.0)) - 0.0) < 5.0  # ahead, to (0, 0)


# ---- the session: commands ------------------------------------------------------------


def test_commands_are_mirrored_into_the_servers_frame():
    assert rcss_command(("turn", 30.0)) == "(turn -30)"  # to our left = counter-clockwise = negative there
    assert rcss_command(("dash", 80.0)) == "(dash 80)"
    assert rcss_command(("dash", 80.0, 90.0)) == "(dash 80 -90)"
    assert rcss_command(("kick", 55.556, -10.0)) == "(kick 55.56 10)"
    assert rcss_command(("move", -10.0, 5.0)) == "(move -10 -5)"
    assert rcss_command(("tackle", 30.0)) == "(tackle -30)"  # protocol 12+: a direction, not a power
    assert rcss_command(("turn_neck", -45.0)) == "(turn_neck 45)"
    assert rcss_command(("say", 'hi "there"&you')) == '(say "hi thereyo")'
    assert rcss_command(("say",)) is None


def test_a_move_before_kick_off_places_a_right_player_in_its_own_half():
    b = _belief("r", 4)
    b.update(parse("(sense_body 0 (speed 0 0) (head_angle 0) (move 0))"))
    b.sent(parse("(move -20 5)"))
    b.update(parse("(sense_body 1 (speed 0 0) (head_angle 0) (move 1))"))  # the server executed it
    assert (b.me.x, b.me.y) == (20.0, -5.0)  # the server mirrors the right team's move


def test_in_a_pause_a_command_the_server_did_not_execute_in_two_steps_is_dropped():
    """The clock stands still at 0 before the kick-off; the server steps on. A move lost there is not
    applied when some later move of ours (asked for elsewhere, never sent through here) is counted."""
    b = _belief()
    b.update(parse("(sense_body 0 (speed 0 0) (head_angle 0) (move 0))"))
    x = b.me.x
    b.sent(parse("(move -20 5)"))
    for _ in range(3):
        b.update(parse("(sense_body 0 (speed 0 0) (head_angle 0) (move 0))"))
    assert not b.pending
    b.update(parse("(sense_body 0 (speed 0 0) (head_angle 0) (move 1))"))
    assert b.me.x == x


def test_turns_and_moves_count_only_once_the_server_executed_them():
    b = _belief()
    b.update(parse("(sense_body 3 (speed 0 0) (head_angle 0) (turn 2) (move 1))"))
    body = b.me.body
    b.sent(parse("(turn 40)"))
    b.update(parse("(sense_body 4 (speed 0 0) (head_angle 0) (turn 2) (move 1))"))  # late: not executed yet
    assert b.me.body == body
    b.update(parse("(sense_body 5 (speed 0 0) (head_angle 0) (turn 3) (move 1))"))  # executed a cycle later
    assert b.me.body == pytest.approx(body + 40.0)
    b.sent(parse("(turn 40)"))
    for t in (6, 7, 8):  # never executed (a replay, or lost): dropped, never applied later
        b.update(parse(f"(sense_body {t} (speed 0 0) (head_angle 0) (turn 3) (move 1))"))
    b.update(parse("(sense_body 9 (speed 0 0) (head_angle 0) (turn 4) (move 1))"))  # someone else's turn
    assert b.me.body == pytest.approx(body + 40.0) and not b.pending
    x = b.me.x
    b.sent(parse("(move -20 5)"))
    b.update(parse("(sense_body 10 (speed 0 0) (head_angle 0) (turn 4) (move 1))"))
    assert b.me.x == x


class TwoBodyCommands(Skill):
    """A skill that asks for more than the server takes in one cycle."""

    name = "greedy"

    def _step(self, world, me):
        return __import__("cf_sim_backend.skills", fromlist=["Step"]).Step(
            [("dash", 50.0), ("turn", 10.0), ("turn_neck", 5.0), ("kick", 10.0, 0.0)]
        )


def replay_acting(skills: list[Skill]) -> tuple[dict[int, list[str]], PlayerSession]:
    """Feed the synch trace to a session; at each (think) run one step of the current skill.

    What was sent, by server step (a sense_body each: the clock stands still in some play modes)."""
    session, sent = PlayerSession("PyTest"), {}
    queue = list(skills)
    for direction, msg in read_trace(SYNCH):
        if direction != "P<":
            continue
        kind = session.receive(_text(msg))
        if kind == "think":
            if session.skill is None and queue:
                session.start(queue.pop(0))
            sent.setdefault(session.belief.steps, []).extend(session.act().commands)
            sent[session.belief.steps].extend(session.act().commands)  # a second act in one step sends nothing
    return sent, session


def _text(msg) -> str:
    from cf_lang.sexp import dumps

    return dumps(msg)


def test_at_most_one_well_formed_body_command_per_cycle_over_a_whole_trace():
    skills: list[Skill] = [
        TwoBodyCommands(),
        MoveTo(-20.0, 10.0, 80.0),
        Intercept(52.5, 0.0),
        KickTo("shoot", 52.5, 0.0, None),
    ]
    skills += [Intercept(52.5, 0.0) for _ in range(20)]
    sent, session = replay_acting(skills)
    commands = [c for cycle in sent.values() for c in cycle]
    assert len(sent) > 900 and len(commands) > 300
    assert all(well_formed(c) for c in commands), [c for c in commands if not well_formed(c)][:5]
    for t, cycle in sent.items():
        body = [c for c in cycle if c[1:].split(" ")[0].rstrip(")") in BODY]
        assert len(body) <= 1, (t, cycle)
    assert session.stats["body_commands"] == sum(
        1 for cycle in sent.values() if any(c[1:].split(" ")[0] in BODY for c in cycle)
    )
    assert sent[min(sent)][:2] == ["(dash 50)", "(turn_neck -5)"]  # the greedy skill's first body command only


def test_skills_from_the_framework_language_run_on_the_belief():
    _, session = replay_acting([])
    b = session.belief
    world = b.world()
    me = world.player(Side.LEFT, 1)
    target = AbsolutePositioning(x=0.0, y=0.0)
    skill = skill_for("moveTo", act.MoveTo(target=target, speed=60.0), Side.LEFT, world, me)
    step = skill.step(world, me)
    assert step.commands and step.commands[0][0] in ("dash", "turn")
    with pytest.raises(ValueError, match="not kickable"):
        far = world.ball.x + 30.0
        world.ball.x = far
        skill_for("kick", act.Kick(power=50.0, direction=0.0), Side.LEFT, world, me)


def test_nothing_is_sent_once_time_is_over():
    _, session = replay_acting([])
    b = session.belief
    world = b.world()
    me = world.player(Side.LEFT, 1)
    session.start(
        skill_for("moveTo", act.MoveTo(target=AbsolutePositioning(x=0.0, y=0.0), speed=60.0), Side.LEFT, world, me)
    )
    b.mode = "time_over"
    b.time += 1
    assert session.act().commands == []


# ---- bad input --------------------------------------------------------------------------


@pytest.mark.parametrize("data", [b"\xff\xfe(see", b"(see 3 ((f c) 1", b"))(", b"", b"(" * 100 + b")" * 100])
def test_unreadable_datagrams_are_counted_and_change_nothing(data):
    session = PlayerSession("CF")
    session.receive(b"(init l 3 before_kick_off)\0")
    assert session.receive(data) == "bad"
    assert session.stats["bad_messages"] == 1 and session.belief.number == 3 and session.belief.errors
    assert session.receive(b"(sense_body 1 (speed 0 0) (head_angle 0))\0") == "sense_body"


def test_server_errors_are_kept_and_the_hello_says_who_we_are():
    session = PlayerSession("CF", goalie=True)
    assert session.hello() == "(init CF (version 19) (goalie))" and well_formed(session.hello())
    assert session.reconnect(4) == "(reconnect CF 4)" and session.belief.number == 4
    session.receive(b"(error no_more_player_or_goalie_or_illegal_client_version)\0")
    assert session.belief.errors == ["no_more_player_or_goalie_or_illegal_client_version"] and not session.ready


def test_a_see_is_expected_every_second_cycle_at_normal_width():
    b = _belief()
    b.update(parse("(sense_body 1 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    assert b.expects_see()  # none seen yet
    b.update(parse(f"(see 1 {SEE_CENTRE})"))
    assert not b.expects_see()
    b.update(parse("(sense_body 2 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    assert not b.expects_see()
    b.update(parse("(sense_body 3 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    assert b.expects_see()


def test_commands_the_server_executed_are_counted_from_its_counters_also_before_kick_off():
    session = PlayerSession("CF")
    session.receive(b"(init l 3 before_kick_off)\0")
    for text in (
        "(sense_body 0 (kick 0) (dash 0) (turn 0) (move 0))",
        "(sense_body 0 (kick 0) (dash 0) (turn 0) (move 1))",
    ):
        session.receive(text.encode())
    session.receive(b"(sense_body 1 (kick 1) (dash 2) (turn 0) (move 1))")
    assert session.stats["executed"] == 4 and session.stats["cycles"] == 2


def test_a_body_command_the_next_sense_body_does_not_count_is_reported_by_kind():
    session = PlayerSession("CF")
    session.receive(b"(init l 3 play_on)\0")
    session.receive(b"(sense_body 5 (kick 2) (dash 7) (turn 0) (move 1))")
    session.skill = _Fixed([("kick", 40.0, 0.0)])
    assert session.act().commands == ["(kick 40 0)"]
    session.receive(b"(sense_body 6 (kick 2) (dash 7) (turn 0) (move 1))")  # the kick did not count
    session.skill = _Fixed([("dash", 50.0)])
    session.act()
    session.receive(b"(sense_body 7 (kick 2) (dash 8) (turn 0) (move 1))")  # the dash did
    assert session.stats.get("unexecuted_kick") == 1 and "unexecuted_dash" not in session.stats
    assert session.unexecuted == ["kick sent at 5 (play_on)"]


class _Fixed(Skill):
    """A skill that sends the same commands every cycle (for the session's bookkeeping)."""

    name = "fixed"

    def __init__(self, commands):
        super().__init__()
        self.commands = commands

    def _step(self, world, me):
        from cf_sim_backend.skills import Step

        return Step(list(self.commands))


def test_a_move_started_after_a_goal_is_refused_once_the_kick_off_is_called():
    session = PlayerSession("CF")
    session.receive(b"(init l 3 goal_l_1)\0")
    session.receive(b"(sense_body 40 (kick 2) (dash 7) (turn 0) (move 1))")
    world = session.belief.world()
    me = world.player(Side.LEFT, 3)
    session.start(skill_for("move", act.Move(target=AbsolutePositioning(x=-10.0, y=5.0)), Side.LEFT, world, me))
    session.receive(b"(hear 41 referee kick_off_r)")  # the server's goal pause ended first
    session.receive(b"(sense_body 41 (kick 2) (dash 7) (turn 0) (move 1))")
    acted = session.act()
    assert acted.commands == [] and acted.status == "failed" and "before a kick-off" in acted.reason
    with pytest.raises(ValueError, match="before a kick-off"):
        skill_for("move", act.Move(target=AbsolutePositioning(x=-10.0, y=5.0)), Side.LEFT, session.belief.world(), me)


def test_while_the_clock_stands_still_each_server_step_takes_a_body_command():
    """The clock stands still before a kick-off (and after a goal, at an offside or a foul) while the
    server goes on stepping: a move asked for after this game time's dash still goes out."""
    session = PlayerSession("CF")
    session.receive(b"(init l 3 play_on)\0")
    session.receive(b"(sense_body 65 (kick 2) (dash 7) (turn 0) (move 1))")
    world = session.belief.world()
    me = world.player(Side.LEFT, 3)
    session.start(skill_for("dash", act.Dash(power=50.0), Side.LEFT, world, me))
    assert any(c.startswith("(dash") for c in session.act().commands)
    session.receive(b"(hear 65 referee before_kick_off)")  # a trainer's call: the clock stops at 65
    session.receive(b"(sense_body 65 (kick 2) (dash 8) (turn 0) (move 1))")
    world = session.belief.world()
    session.start(skill_for("move", act.Move(target=AbsolutePositioning(x=-10.0, y=5.0)), Side.LEFT, world, me))
    assert session.act().commands[:1] == ["(move -10 -5)"]
    assert not any(c.startswith(("(move", "(dash")) for c in session.act().commands)  # one a step


def test_while_the_clock_stands_still_the_head_looks_round_at_each_see():
    """Before a kick-off the server steps and shows a see every other step, all at one game time:
    the head swings to the other side of the ball at each, as it does in play (it turned once, then stood)."""
    session = PlayerSession("CF")
    session.receive(b"(init l 3 before_kick_off)\0")
    neck, heads = 0.0, []
    for step in range(6):
        session.receive(f"(sense_body 0 (view_mode high normal) (head_angle {neck:g}) (turn_neck {step}))".encode())
        if step % 2 == 0:
            session.receive(f"(see 0 {SEE_CENTRE} ((b) 10 20))".encode())
        turns = [c for c in session.act().commands if c.startswith("(turn_neck")]
        assert len(turns) == (1 if step % 2 == 0 else 0)  # one each see; the head stays between them
        neck += sum(float(t[len("(turn_neck ") : -1]) for t in turns)
        heads.append(round(session.belief.me.body + neck))
    assert heads[0] != heads[2] and heads[0] == heads[4]  # one side of the ball, the other, back


def test_our_executed_kick_sends_the_believed_ball_off_before_the_next_see():
    """The synch trace: a kick at cycle 21 (executed: the kick counter is 1 at 22), no see at 22."""
    from cf_sim_backend.rcss.trace import _truth

    belief, truth, at = Belief("PyTest"), {}, {}
    for direction, msg in read_trace(SYNCH):
        if direction == "T<" and str(msg[0]) == "see_global":
            truth[int(msg[1])] = _truth(msg, "PyTest")["ball"]
        elif direction == "P<" and belief.update(msg) == "sense_body" and belief.time in (22, 23):
            at[belief.time] = (belief.ball.x, belief.ball.y, belief.ball.seen)
        elif direction == "P>":
            belief.sent(msg)
        if belief.time > 24:
            break
    x, y, seen = at[22]
    assert seen == 21 and math.hypot(x - truth[22][0], y - truth[22][1]) < 0.2  # was 2.2 m off (still at our feet)


def _shown(d: float) -> float:
    """The distance rcssserver's see shows for a ball ``d`` away (its quantisation, ball and players)."""
    return round(math.exp(round(math.log(d) / 0.1) * 0.1), 1)


@pytest.mark.parametrize("margin", [0.7, 0.8, 0.9, 1.0])  # the kickable margins of the server's player types
def test_the_skills_kick_every_ball_a_see_shows_surely_in_reach_and_no_other(margin):
    b = Belief("CF")
    b.server.update(player_size=0.3, ball_size=0.085, kickable_margin=margin)
    reach, skills = 0.385 + margin, b.params().kickable_distance
    truths = [i / 1000 for i in range(300, 2000)]
    for d in truths:
        if _shown(d) <= skills:
            assert d <= reach  # never a kick the server refuses
    # and every distance the see shows whose whole band is within reach is played
    surely = {_shown(d) for d in truths} - {_shown(d) for d in truths if d > reach}
    assert all(shown <= skills for shown in surely)
    if margin == 0.7:
        assert _shown(1.04) == 1.0 <= skills < 1.1 == _shown(1.06)  # 1.0: 0.95-1.05 m off; 1.1: maybe 1.16


def _dead_reckoned_errors(our_turn: float | None) -> list[float]:
    """OwnPlayer position error at every sense_body (before that cycle's see) of the synch trace.

    With ``our_turn``, the adapter also sends that turn after every think, as a decision might;
    a replay, like a loaded server that got it late, never executes it.
    """
    from cf_sim_backend.rcss.trace import _truth

    belief, truth, errors = Belief("PyTest"), {}, []
    for direction, msg in read_trace(SYNCH):
        if direction == "T<" and str(msg[0]) == "see_global":
            truth[int(msg[1])] = _truth(msg, "PyTest")
        elif direction == "P<":
            kind = belief.update(msg)
            if kind == "sense_body" and belief.me.localised >= 0 and belief.me.sigma < UNSURE:
                errors.append((belief.time, belief.me.x, belief.me.y))
            if kind == "think" and our_turn is not None:
                belief.sent(parse(f"(turn {our_turn})"))
        elif direction == "P>" and our_turn is None:
            belief.sent(msg)
    return [math.hypot(x - truth[t]["me"][0], y - truth[t]["me"][1]) for t, x, y in errors if "me" in truth.get(t, {})]


def test_turns_the_server_never_executed_do_not_throw_the_dead_reckoned_pose_off():
    """What made the replayed adapter test fail on a loaded machine: a query answered between a
    cycle's sense_body and its see saw our unexecuted turn in the pose (1.12 m off)."""
    recorded = sorted(_dead_reckoned_errors(None))
    ours = sorted(_dead_reckoned_errors(90.0))
    assert len(ours) > 100
    assert ours[-1] < max(1.0, 1.5 * recorded[-1]), (ours[-5:], recorded[-5:])
    assert statistics.mean(ours) < 1.5 * statistics.mean(recorded) + 0.05


def test_while_our_tackle_holds_us_nothing_is_sent():
    session = PlayerSession("CF")
    session.receive(b"(init l 3 play_on)\0")
    session.receive(b"(sense_body 40 (kick 2) (dash 7) (turn 0) (move 1) (tackle (expires 0) (count 0)))")
    session.belief.ball = Track(1.0, 0.0, 0.0, 0.0, 0.1, 40)
    world = session.belief.world()
    me = world.player(Side.LEFT, 3)
    session.start(skill_for("tackle", act.Tackle(power=100.0, direction=0.5), Side.LEFT, world, me))
    assert session.act().commands == ["(tackle -28.65)"]
    session.receive(b"(sense_body 41 (kick 2) (dash 7) (turn 0) (move 1) (tackle (expires 9) (count 1)))")
    assert session.belief.counters["tackle"] == 1 and session.belief.world().player(Side.LEFT, 3).frozen == 9
    session.start(MoveTo(-20.0, 10.0, 80.0))
    assert session.act().commands == []  # the server would ignore a dash now
    session.receive(b"(sense_body 50 (kick 2) (dash 7) (turn 0) (move 1) (tackle (expires 0) (count 1)))")
    assert session.act().commands  # free again
    assert session.stats.get("unexecuted_dash", 0) == 0


def next_step(b: Belief, t: int, seen: bool = False) -> None:
    """The server's next step, at game time ``t``, as its sense_body (and, if ``seen``, its see) would leave the belief."""
    b.time = b.sense_time = t
    b.steps += 1
    if seen:
        b.see_time = t
        b.sees += 1


def test_the_head_sweeps_round_the_ball_a_see_at_a_time_and_the_field_without_one():
    session = PlayerSession("CF")
    session.receive(b"(init l 3 play_on)\0")
    session.receive(b"(sense_body 40 (head_angle 0) (kick 2) (dash 7) (turn 0) (move 1))")
    b = session.belief
    assert session.act().commands == []  # not placed yet: no idea where the head would point
    b.me.localised = b.see_time = 40
    b.ball = Track(10.0, 10.0, 0.0, 0.0, 0.1, 40)  # 45 degrees off our body (server frame)
    heads = []
    for t in (40, 42, 44):
        first = session.act().commands
        assert session.act().commands == []  # one turn_neck a cycle
        (turn,) = first
        b.me.neck += float(turn[len("(turn_neck ") : -1])
        heads.append(round(b.me.head))
        next_step(b, t + 2, seen=True)
    assert heads == [5, 85, 5]  # the ball (at 45) stays 40 degrees inside a 120-degree cone, left then right


def test_with_the_ball_lost_the_head_sweeps_round_a_cone_width_a_see_the_way_the_body_turns():
    from cf_sim_backend.skills import Once

    session = placed_session()
    b = session.belief
    b.ball = None  # lost: the decision turns the body a radian a cycle to look for it
    covered = set()
    for t in range(41, 49):  # a see every other cycle at the normal width: four sees
        next_step(b, t)
        session.start(Once(("turn", -57.3), "turn"))
        look(session)
        if t % 2:
            b.see_time = t
            b.sees += 1
            covered |= {round(norm_deg(b.me.head + a)) for a in range(-60, 61)}
    # Four sees of a 120-degree cone see all round. Swinging the neck from limit to limit while the
    # body turned left 47 degrees unseen after four sees, and 5 after six.
    assert len(covered) >= 359


def placed_session() -> PlayerSession:
    """CF 3 on the left at cycle 40, placed on the field, the head straight, the view normal."""
    session = PlayerSession("CF")
    session.receive(b"(init l 3 play_on)\0")
    session.receive(b"(sense_body 40 (view_mode high normal) (head_angle 0) (kick 2) (dash 7) (turn 0) (move 1))")
    session.belief.me.localised = session.belief.see_time = 40
    return session


def test_the_head_sweep_allows_for_the_bodys_turn_in_the_same_cycle():
    from cf_sim_backend.skills import TurnTo

    session = placed_session()
    b = session.belief
    b.ball = Track(20.0, 0.0, 0.0, 0.0, 0.1, 40)  # straight ahead (server frame), too far for the narrow view
    session.start(TurnTo(heading=60.0))
    turn, neck = session.act().commands
    body = float(turn[len("(turn ") : -1])  # standing still: the body turns by the whole moment
    head = body + b.me.neck + float(neck[len("(turn_neck ") : -1])
    assert abs(body) > 30.0 and abs(abs(head) - 40.0) < 1.0  # still 40 degrees off the ball


def test_near_the_ball_the_view_narrows_to_a_see_every_cycle_and_the_head_keeps_the_ball_inside_it():
    session = placed_session()
    b = session.belief
    b.ball = Track(8.0, 8.0, 0.0, 0.0, 0.1, 40)  # 11 m off, 45 degrees off our body: between the two widths
    assert not any("change_view" in c for c in session.act().commands)
    next_step(b, 41)
    b.ball = Track(6.0, 6.0, 0.0, 0.0, 0.1, 40)  # 8.5 m: watch it every cycle
    view, neck = session.act().commands
    assert view == "(change_view narrow)" and well_formed(view)
    head = b.me.neck + float(neck[len("(turn_neck ") : -1])
    assert abs(abs(45.0 - head) - 15.0) < 1.0  # 15 degrees inside the 60-degree cone, not 40 (out of it)
    assert session.act().commands == []  # once a cycle
    session.receive(b"(sense_body 42 (view_mode high narrow) (head_angle 0) (kick 2) (dash 7) (turn 0) (move 1))")
    assert b.me.view_width == "narrow" and b.expects_see()  # a see every cycle now
    b.ball = Track(9.0, 9.0, 0.0, 0.0, 0.1, 40)  # 12.7 m: inside the gap, stays narrow
    assert not any("change_view" in c for c in session.act().commands)
    next_step(b, 43)
    b.ball = Track(20.0, 20.0, 0.0, 0.0, 0.1, 40)  # far: the wider cone, every other cycle
    assert session.act().commands[0] == "(change_view normal)"


def test_with_the_ball_at_its_feet_the_head_looks_round_the_player_a_cone_width_at_a_time():
    session = placed_session()
    b = session.belief
    b.me.view_width = session.view = "narrow"
    b.me.body = 30.0
    b.ball = Track(0.5, 0.3, 0.0, 0.0, 0.1, 40)  # at our feet: seen within 3 m wherever we look
    necks = []
    for t in (41, 42, 43, 44):
        next_step(b, t, seen=True)
        commands = [c for c in session.act().commands if c.startswith("(turn_neck")]
        b.me.neck += float(commands[0][len("(turn_neck ") : -1]) if commands else 0.0
        necks.append(round(b.me.neck))
    # Left of the body, ahead, right, left again: the 60-degree cones cover 180 degrees in three sees.
    assert necks[3] == necks[0] and sorted(necks[:3]) == [-60, 0, 60]
    b.ball = Track(3.0, 3.0, 0.0, 0.0, 0.1, 44)  # 4 m off: the head goes back to the ball
    for t in (45, 46):
        next_step(b, t, seen=True)
        commands = [c for c in session.act().commands if c.startswith("(turn_neck")]
        b.me.neck += float(commands[0][len("(turn_neck ") : -1]) if commands else 0.0
        assert abs(abs(45.0 - b.me.head) - 15.0) < 1.0  # 15 degrees off the ball, inside the narrow cone


def look(session: PlayerSession) -> None:
    """One cycle's act, with its turn and turn_neck carried out (a still player turns by the whole moment)."""
    for command in session.act().commands:
        name, _, value = command.strip("()").partition(" ")
        if name == "turn":
            session.belief.me.body = norm_deg(session.belief.me.body + float(value))
        elif name == "turn_neck":
            session.belief.me.neck += float(value)


def test_going_for_a_rolling_ball_every_other_see_looks_upfield_until_it_is_close():
    session = placed_session()
    b = session.belief
    b.me.view_width = session.view = "narrow"
    b.me.body = 90.0  # facing the ball: the skill dashes, the body stays
    b.ball = Track(0.0, 12.0, 0.0, -1.5, 0.1, 40)  # 12 m off, rolling at us at 1.5 m/cycle: 8 cycles
    session.start(Intercept(52.5, 0.0))
    heads, seen = [], 41  # the see at 41 showed it
    for t in (41, 42, 43):
        next_step(b, t, seen=True)
        b.ball.seen = seen
        look(session)
        heads.append(round(b.me.head))
        seen = t + 1 if abs(norm_deg(90.0 - b.me.head)) <= 30.0 else seen  # the next see shows it if in the cone
    assert heads[0] == 0  # towards their goal, away from the ball at 90
    assert abs(heads[1] - 90) <= 15 and heads[2] == 0  # back to the ball, then upfield again
    b.ball = Track(0.0, 3.0, 0.0, -1.5, 0.1, 43)  # two cycles off: the head stays on the ball
    next_step(b, 44, seen=True)
    b.ball.seen = 44
    look(session)
    assert abs(b.me.head - 90.0) <= 15.0
    session.start(None)  # not going for it: the usual look, near the ball
    b.ball = Track(0.0, 12.0, 0.0, -1.5, 0.1, 44)
    next_step(b, 45, seen=True)
    b.ball.seen = 45
    look(session)
    assert abs(b.me.head - 90.0) <= 15.0
    session.goalie = True  # the goalkeeper going for a ball (a shot, maybe) keeps his eyes on it
    session.start(Intercept(52.5, 0.0))
    next_step(b, 46, seen=True)
    b.ball.seen = 46
    look(session)
    assert abs(b.me.head - 90.0) <= 15.0


def test_a_team_mates_say_is_heard_into_the_world_state_and_others_are_not():
    """rcssserver 19: ``(hear T DIR our N "text")`` from a team-mate; ``(hear T our N)`` over the capacity;
    an opponent's ``(hear T DIR opp "text")`` is not ours to read."""
    b = _belief()
    b.update(parse("(sense_body 20 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    for line in ('(hear 20 -30 our 9 "t0725310")', "(hear 20 our 4)", '(hear 20 12 opp "ha")', '(hear 20 self "p9")'):
        b.update(parse(line))
    state = world_state(b)
    assert [(h.player_number, h.message, h.time) for h in state.heard] == [(9, "t0725310", 20)]
    b.update(parse("(sense_body 22 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    assert world_state(b).heard == ()  # two cycles on: no longer news


def test_a_say_goes_out_with_the_next_cycles_commands_beside_the_skill_in_force():
    session = PlayerSession("CF")
    session.receive(b"(init l 7 before_kick_off)\0")
    session.receive(b"(sense_body 0 (view_mode high normal) (speed 0 0) (head_angle 0))\0")
    session.say("p9")
    first = session.act().commands
    assert '(say "p9")' in first and all(well_formed(c) for c in first)
    assert not any(c.startswith("(say") for c in session.act().commands)  # said once


@pytest.mark.parametrize("text", ["", "a say too long", 'q"uote', "caf\u00e9"])
def test_a_say_rcssserver_would_not_carry_is_refused_with_why(text):
    b = _belief()
    b.update(parse("(sense_body 1 (view_mode high normal) (speed 0 0) (head_angle 0))"))
    world = b.world()
    with pytest.raises(SkillError, match="a say carries"):
        skill_for("say", act.Say.model_construct(message=text), Side.LEFT, world, world.player(Side.LEFT, 7))
