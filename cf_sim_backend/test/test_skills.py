"""Skills turn Framework Language actions into simulator commands; run them in the real simulator core."""

from __future__ import annotations

import math

import pytest
from test_sim_core import QUIET, sim_with

from cf_lang import parse_expr
from cf_sim_backend import skills
from cf_sim_backend.embedded.physics import tackle_failure
from cf_sim_backend.skills import FIRST_TOUCHES, SkillError, intercept_point, skill_for
from cf_sim_backend.world import Params, Side, distance


def run(sim, side, number, text, cycles=300):
    """Carry out an exec on the simulator until the skill ends; return (status, cycles)."""
    skill, me = skill_of(sim, side, number, text)
    for _ in range(cycles):
        step = skill.step(sim.world, me)
        for cmd in step.commands:
            if cmd[0] != "say":
                sim.command(side, number, cmd[0], *cmd[1:])
        sim.step()
        if step.status != "running":
            return step.status, skill.cycles
    return "running", skill.cycles


def cycle(sim, skill, me, kinds):
    """One cycle of ``skill`` for ``me`` on the simulator; its commands' kinds go into ``kinds``."""
    step = skill.step(sim.world, me)
    for cmd in step.commands:
        kinds.append(cmd[0])
        sim.command(me.side, me.number, cmd[0], *cmd[1:])
    sim.step()
    return step


def skill_of(sim, side, number, text):
    """The skill an exec starts for player ``number``, and the player."""
    me = sim.world.player(side, number)
    return skill_for("", parse_expr(text).action, side, sim.world, me), me


def exec_(method, args="", number=7):
    return f"(exec Player {method} :playerNumber {number} :whichTeam our {args})"


@pytest.mark.parametrize("side", [Side.LEFT, Side.RIGHT])
def test_move_to_in_own_frame(side):
    sim = sim_with((side, 7, 0.0, 0.0, 0.0))
    status, _ = run(sim, side, 7, exec_("moveTo", ":target (AbsolutePositioning :x 10 :y 5)"))
    me = sim.world.player(side, 7)
    assert status == "done"
    # (10, 5) in the player's own frame: (-10, -5) in the absolute one for the right side.
    assert distance(me.x, me.y, 10 * side.sign, 5 * side.sign) < 1.0


def test_intercept_then_shoot_scores():
    sim = sim_with((Side.LEFT, 9, 20.0, 10.0, 90.0))
    sim.world.ball.x, sim.world.ball.y, sim.world.ball.vx = 30.0, 0.0, 0.5
    assert run(sim, Side.LEFT, 9, exec_("intercept", number=9))[0] == "done"
    assert run(sim, Side.LEFT, 9, exec_("shoot", number=9))[0] == "done"
    for _ in range(60):
        sim.step()
    assert sim.world.score[Side.LEFT] == 1


def test_pass_reaches_the_team_mate():
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 15.0, 10.0, 0.0))
    sim.world.ball.x = 0.6
    assert run(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4))[0] == "done"
    closest = 99.0
    for _ in range(80):
        sim.step()
        closest = min(closest, distance(sim.world.ball.x, sim.world.ball.y, 15.0, 10.0))
    assert closest < 3.0


def test_dribble_keeps_the_ball_to_the_target():
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0))
    sim.world.ball.x = 0.6
    status, _ = run(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10), 400)
    assert status == "done" and distance(sim.world.ball.x, sim.world.ball.y, 15.0, 0.0) <= 1.6


def test_an_open_run_at_full_speed_gets_there_sooner_than_close_control_and_keeps_the_ball_near():
    cycles, furthest = {}, {}
    for speed in (70, 100):
        sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0))
        sim.world.ball.x = 0.6
        target = f":target (AbsolutePositioning :x 25 :y 0) :speed {speed}"
        skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", target, 10))
        ball, furthest[speed] = sim.world.ball, 0.0
        for cycles[speed] in range(1, 400):
            step = skill.step(sim.world, me)
            for cmd in step.commands:
                sim.command(Side.LEFT, 10, cmd[0], *cmd[1:])
            sim.step()
            furthest[speed] = max(furthest[speed], distance(me.x, me.y, ball.x, ball.y))
            if step.status != "running":
                break
        assert step.status == "done" and distance(ball.x, ball.y, 25.0, 0.0) <= 2.0
        assert distance(me.x, me.y, ball.x, ball.y) < 2.5  # still his ball
    assert cycles[100] < cycles[70]
    # Each touch sends the ball no further than he is REGAIN cycles later: it stays within a stride
    # (a fixed 1.3 m/cycle push ran 2.9 m ahead and was touched again only 12 cycles on).
    assert furthest[100] < 2.0


def test_dribble_runs_after_a_pushed_ball_instead_of_kicking_it_again():
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 20.0))
    sim.world.ball.x, sim.world.ball.y = -0.3, 0.7  # beside him: after the push it is still in reach
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10))
    kinds = []
    for _ in range(12):
        for cmd in skill.step(sim.world, me).commands:
            kinds.append(cmd[0])
            sim.command(Side.LEFT, 10, cmd[0], *cmd[1:])
        sim.step()
    # A push, then dashes while the ball rolls on ahead: never two kicks in a row.
    assert kinds[0] == "kick" and kinds[1] == "dash"
    assert "kick kick" not in " ".join(kinds)
    assert me.x > 4.0


def test_turn_to_object_and_direction():
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, 0.0), (Side.RIGHT, 3, 0.0, 10.0, 0.0))
    assert run(sim, Side.LEFT, 6, exec_("turnToObject", ":obj (Player :playerNumber 3 :whichTeam opp)", 6))[0] == "done"
    assert sim.world.player(Side.LEFT, 6).body == pytest.approx(90.0, abs=5.1)
    assert run(sim, Side.LEFT, 6, exec_("turnToDirection", ":direction 3.14159", 6))[0] == "done"
    assert abs(sim.world.player(Side.LEFT, 6).body) == pytest.approx(180.0, abs=5.1)


def test_kick_power_and_head():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0))
    sim.world.ball.x = 0.5
    assert run(sim, Side.LEFT, 2, exec_("kick", f":power 50 :direction {math.pi / 2}", 2))[0] == "done"
    assert sim.world.ball.vy > 0.5 and abs(sim.world.ball.vx) < 0.1
    assert run(sim, Side.LEFT, 2, exec_("turnHead", ":angle 0.5", 2))[0] == "done"
    assert sim.world.player(Side.LEFT, 2).neck == pytest.approx(math.degrees(0.5))


@pytest.mark.parametrize(
    ("text", "words"),
    [
        (exec_("kick", ":power 50 :direction 0", 2), "not kickable"),
        (exec_("catch", ":direction 0", 2), "only the goalkeeper"),
        (exec_("move", ":target (AbsolutePositioning :x -10 :y 0)", 2), "only before a kick-off"),
        (exec_("pass", ":to (Player :playerNumber 9 :whichTeam our)", 2), "no team-mate number 9"),
    ],
)
def test_impossible_actions_are_refused_with_a_reason(text, words):
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), params=Params(**{**QUIET.__dict__}))
    sim.world.ball.x = 20.0
    with pytest.raises(SkillError, match=words):
        skill_for("", parse_expr(text).action, Side.LEFT, sim.world, sim.world.player(Side.LEFT, 2))


def test_a_tackle_hits_by_rcssservers_odds_and_holds_the_tackler():
    sim = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 3, 2.0, 0.0, 180.0))
    w = sim.world
    w.ball.x, w.ball.y = 1.2, 0.0  # in front of both; the opponent has it at his feet
    assert tackle_failure(w, w.player(Side.LEFT, 2)) == pytest.approx((1.2 / 2.0) ** 6)
    w.ball.x = -1.0
    assert tackle_failure(w, w.player(Side.LEFT, 2)) == 1.0  # behind the body: no tackle
    w.ball.x = 1.2
    me = w.player(Side.LEFT, 2)
    # A pass request whose ball an opponent holds: the approach tackles towards the target.
    skill = skill_for(
        "pass", parse_expr(exec_("pass", ":target (AbsolutePositioning :x 0 :y 20)", 2)).action, Side.LEFT, w, me
    )
    step = skill.step(w, me)
    assert step.commands[0][0] == "tackle" and step.commands[0][1] == pytest.approx(
        math.degrees(math.atan2(20.0, -1.2))
    )
    sim.command(Side.LEFT, 2, *step.commands[0])
    sim.step()
    assert w.ball.vy > 1.0 and me.frozen == w.params.tackle_cycles - 1
    sim.command(Side.LEFT, 2, "dash", 100.0)
    sim.step()
    assert abs(me.vx) < 0.05  # held: the dash did not count
    far = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 3, 3.5, 0.0, 180.0))
    far.world.ball.x = 1.9  # loose, or too far for a sure tackle: run for it instead
    skill, me = skill_of(far, Side.LEFT, 2, exec_("pass", ":target (AbsolutePositioning :x 0 :y 20)", 2))
    assert skill.step(far.world, me).commands[0][0] != "tackle"


def test_an_intercept_tackles_a_ball_an_opponent_holds_towards_their_goal():
    for side in (Side.LEFT, Side.RIGHT):
        body = 0.0 if side is Side.LEFT else 180.0
        sim = sim_with((side, 2, 0.0, 0.0, body), (side.other, 3, 2.0 * side.sign, 0.0, body + 180.0))
        w = sim.world
        w.ball.x = 1.2 * side.sign  # in front of me; the opponent has it at his feet
        skill, me = skill_of(sim, side, 2, exec_("intercept", "", 2))
        step = skill.step(w, me)
        assert step.commands[0][0] == "tackle" and step.commands[0][1] == pytest.approx(0.0, abs=1e-6)
        sim.command(side, 2, *step.commands[0])
        sim.step()
        assert w.ball.vx * side.sign > 1.0  # on its way to their goal
    loose = sim_with((Side.LEFT, 2, 0.0, 0.0, 0.0), (Side.RIGHT, 3, 9.0, 0.0, 180.0))
    loose.world.ball.x = 1.2  # nobody else on it: the intercept just goes for it
    skill, me = skill_of(loose, Side.LEFT, 2, exec_("intercept", "", 2))
    assert skill.step(loose.world, me).commands[0][0] != "tackle"


def test_near_our_goal_no_tackle_through_a_man_as_rcssserver_would_call_a_foul():
    # Right 9 stands between me and the ball at his feet, facing its way: near our goal I do not
    # tackle through him (a foul half the time), further out I do; facing me, he is no foul's victim.
    # The corner of our penalty area, 25.3 m out, counts: a foul there is an indirect free kick. A man
    # 0.8 m off the way to the ball (0.2 m outside the referee's place) counts too: beliefs err.
    cases = (
        (-35.0, 0.0, 0.0, 0.0, False),
        (-20.0, 0.0, 0.0, 0.0, True),
        (-35.0, 0.0, 0.0, 180.0, True),
        (-37.0, 20.0, 0.0, 0.0, False),
        (-35.0, 0.0, 0.8, 0.0, False),
    )
    for x, y, aside, body, tackles in cases:
        sim = sim_with((Side.LEFT, 2, x, y, 0.0), (Side.RIGHT, 9, x + 0.8, y + aside, body))
        w = sim.world
        w.ball.x, w.ball.y = x + 1.4, y
        skill, me = skill_of(sim, Side.LEFT, 2, exec_("intercept", "", 2))
        assert (skill.step(w, me).commands[0][0] == "tackle") is tackles, x


def kick_commands(sim, skill, me, cycles):
    """Run a kicking skill on the simulator: the kinds of command it sent, and the fastest the ball left.

    Fails if the referee calls a free kick fault (a set piece's taker touched the ball twice).
    """
    kinds, speed = [], 0.0
    for _ in range(cycles):
        step = skill.step(sim.world, me)
        for cmd in step.commands:
            kinds.append(cmd[0])
            sim.command(me.side, me.number, *cmd)
        sim.step()
        assert not sim.world.mode.startswith("free_kick_fault")
        speed = max(speed, math.hypot(sim.world.ball.vx, sim.world.ball.vy) / sim.world.params.ball_decay)
        if step.status == "done":
            break
    return kinds, speed


def test_a_pass_from_a_ball_beside_the_body_is_laid_first_and_leaves_at_the_speed_it_wants():
    def pass_from(bx, by, first_touches: bool) -> tuple[list[str], float]:
        sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 20.0, 0.0, 0.0))
        sim.world.ball.x, sim.world.ball.y = bx, by
        skill, me = skill_of(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4))
        skill.touches = 0 if first_touches else FIRST_TOUCHES
        return kick_commands(sim, skill, me, 5)

    for bx, by in ((0.1, 1.0), (-0.6, -0.5), (0.0, -0.9)):  # beside the body, behind it, at the edge
        kinds, laid = pass_from(bx, by, True)
        assert kinds in (["kick", "kick"], ["kick", "kick", "kick"])
        _, direct = pass_from(bx, by, False)
        assert laid >= 0.95 * 2.7 > 1.25 * direct  # the pass wants 2.7 m/cycle; one touch gives 2.0 or less


def test_a_shots_first_touch_sets_the_ball_rolling_so_the_kick_sends_it_faster_than_a_still_ball_can_go():
    def kick_from(bx, by, method):
        sim = sim_with((Side.LEFT, 9, 35.0, 0.0, 0.0))
        sim.world.ball.x, sim.world.ball.y = 35.0 + bx, by
        target = ":target (AbsolutePositioning :x 53.5 :y -6.2) :power 100.0"
        skill, me = skill_of(sim, Side.LEFT, 9, exec_(method, target, 9))
        return kick_commands(sim, skill, me, 5)

    prm = Params()
    for bx, by in ((0.1, 1.0), (-0.6, -0.5)):  # beside the body, behind it
        kinds, shot = kick_from(bx, by, "shoot")
        assert kinds == ["kick", "kick"]
        assert shot > 0.95 * prm.ball_speed_max > prm.ball_accel_max  # one kick of a still ball: 2.7 at most
        _, long_ball = kick_from(bx, by, "pass")  # a kick at full power that is not a shot is set up for 2.7
        assert long_ball < 0.95 * prm.ball_speed_max
    kinds, _ = kick_from(0.5, 0.0, "shoot")  # in front: no touch makes the kick faster, so none is taken
    assert kinds == ["kick"]


def test_a_first_touch_lays_the_ball_out_of_an_opponents_way_and_is_skipped_when_none_is_clear():
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 20.0, 0.0, 0.0), (Side.RIGHT, 5, 2.0, -2.6, 90.0))
    sim.world.ball.x, sim.world.ball.y = 0.1, 1.0  # beside the body; he comes up on the other side
    skill, me = skill_of(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4))
    step = skill.step(sim.world, me)
    assert step.commands[0][0] == "kick" and skill.touches == 1
    sim.command(Side.LEFT, 4, *step.commands[0])
    sim.step()
    b, him = sim.world.ball, sim.world.player(Side.RIGHT, 5)
    assert distance(b.x, b.y, him.x, him.y) >= skills.LAY_CLEAR
    assert distance(b.x, b.y, me.x, me.y) <= sim.world.params.kickable_distance
    # Three men round him a little further off: every spot he could lay it on is within their reach.
    crowd = ((Side.RIGHT, 5, 0.0, 3.3, 0.0), (Side.RIGHT, 6, 0.0, -3.3, 0.0), (Side.RIGHT, 7, -3.3, 0.0, 0.0))
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 20.0, 0.0, 0.0), *crowd)
    sim.world.ball.x, sim.world.ball.y = 0.1, 1.0
    status, cycles = run(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4), 5)
    assert status == "done" and cycles == 2  # kicked at once, slow as it is


def test_a_ball_lying_where_a_collecting_touch_would_lay_it_is_kicked_at_once():
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 20.0, 0.0, 0.0))
    b = sim.world.ball
    b.x, b.y, b.vx = 0.6, 0.0, -0.1  # in front of the body, rolling back a little: one touch gives ~2.4 of 2.7
    status, cycles = run(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4), 5)
    assert status == "done" and cycles == 2  # the kick, then done: no touch that leaves it where it lay
    assert b.vx > 1.5


def test_the_taker_of_a_set_piece_steps_up_to_the_ball_and_touches_it_once():
    def set_piece_pass(ball: tuple[float, float], mode: str) -> tuple[list[str], float]:
        sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 25.0, 0.0, 0.0))
        sim.world.ball.x, sim.world.ball.y = ball
        sim.world.mode = mode
        skill, me = skill_of(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4))
        return kick_commands(sim, skill, me, 8)

    # A kick-off taker 1 m behind the ball: one touch from there gives ~2.1 of the 2.7 wanted.
    kinds, stepped = set_piece_pass((1.0, 0.0), "kick_off_l")
    assert kinds == ["dash", "kick"]
    assert stepped > 2.5
    # Beside the body: he turns to it, steps up, and kicks once: no collecting touch.
    kinds, turned = set_piece_pass((0.1, 1.0), "free_kick_l")
    assert kinds.count("kick") == 1 and kinds[0] == "turn" and len(kinds) <= 4
    assert turned > 2.5
    _, in_play = set_piece_pass((1.0, 0.0), "play_on")  # in play he lays it in front instead
    assert in_play > 2.0


def test_a_pressed_passer_kicks_at_once():
    sim = sim_with((Side.LEFT, 4, 0.0, 0.0, 0.0), (Side.LEFT, 8, 20.0, 0.0, 0.0), (Side.RIGHT, 5, 1.5, 2.0, 180.0))
    sim.world.ball.x, sim.world.ball.y = 0.1, 1.0
    status, cycles = run(sim, Side.LEFT, 4, exec_("pass", ":to (Player :playerNumber 8 :whichTeam our)", 4), 5)
    assert status == "done" and cycles == 2  # the kick, then done: no collecting touch with an opponent at hand


def test_a_ball_close_beside_the_player_is_chased_sideways_and_a_far_one_after_a_turn():
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, 0.0))
    sim.world.ball.x, sim.world.ball.y = 1.0, 2.0  # 2.2 m away, 63 degrees off the body
    skill, me = skill_of(sim, Side.LEFT, 6, exec_("intercept", number=6))
    (cmd,) = skill.step(sim.world, me).commands
    assert cmd[0] == "dash" and cmd[2] == pytest.approx(63, abs=1)
    sim.world.ball.x, sim.world.ball.y = 5.0, 10.0
    (cmd,) = skill.step(sim.world, me).commands
    assert cmd[0] == "turn"


def test_a_goalkeeper_in_his_area_plans_to_meet_a_shot_where_it_comes_within_his_catch():
    def meeting(goalie):
        sim = sim_with((Side.LEFT, 1, -50.0, 0.0, 0.0))
        me = sim.world.player(Side.LEFT, 1)
        me.goalie = goalie
        ball = sim.world.ball
        angle = math.atan2(4.2 + 4.0, -52.5 + 38.0)  # struck from (-38, -4) at the far post
        ball.x, ball.y, ball.vx, ball.vy = -38.0, -4.0, 2.5 * math.cos(angle), 2.5 * math.sin(angle)
        return intercept_point(sim.world, me)

    *_, caught = meeting(goalie=True)
    *_, kicked = meeting(goalie=False)
    assert caught == 4 and kicked == 5  # his catch reaches further than a kick


@pytest.mark.parametrize("velocity", [(0.0, 2.0), (-1.5, 1.0), (1.0, -0.5)])
def test_a_rolling_ball_is_met_where_its_path_and_the_player_first_meet_after_one_turn_at_most(velocity):
    sim = sim_with((Side.LEFT, 6, 0.0, 0.0, 0.0))
    ball = sim.world.ball
    ball.x, ball.y, (ball.vx, ball.vy) = 10.0, -10.0, velocity
    skill, me = skill_of(sim, Side.LEFT, 6, exec_("intercept", number=6))
    x, y, planned = intercept_point(sim.world, me)
    commands = []
    for _ in range(60):
        step = skill.step(sim.world, me)
        if step.status == "done":
            break
        commands += [(cmd[0], distance(me.x, me.y, x, y)) for cmd in step.commands]
        for cmd in step.commands:
            sim.command(Side.LEFT, 6, cmd[0], *cmd[1:])
        sim.step()
    assert step.status == "done"  # the ball is within his reach
    first_dash = next(i for i, (name, _) in enumerate(commands) if name == "dash")
    # He ran straight to the meeting point (a turn at most to face the ball there): no new aim on the way.
    assert [name for name, far in commands[first_dash:] if name == "turn" and far > 1.0] == []
    assert skill.cycles - 1 <= planned + 2  # cycles before the one it was done in (noise may cost one or two)


def test_a_dribble_takes_the_ball_round_a_man_in_its_way_not_into_him():
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0), (Side.RIGHT, 4, 5.0, 0.0, 180.0))
    sim.world.ball.x = 0.6
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10))
    him, closest, pushed, kinds = sim.world.player(Side.RIGHT, 4), 99.0, None, []
    for _ in range(40):
        step = cycle(sim, skill, me, kinds)
        if pushed is None and "kick" in kinds:
            pushed = math.degrees(math.atan2(sim.world.ball.vy, sim.world.ball.vx))
        closest = min(closest, distance(him.x, him.y, sim.world.ball.x, sim.world.ball.y))
        if step.status != "running":
            break
    # A pushed ball would be his first: the dribble keeps it close, round him, never within his
    # reach, and it gets there (taken straight at him it stuck at his feet).
    assert pushed is not None and "dash" in kinds
    assert closest > 1.2
    assert step.status == "done" and distance(sim.world.ball.x, sim.world.ball.y, 15.0, 0.0) <= 1.6


def test_a_ball_touched_back_past_a_dribbler_running_on_is_his_again_only_after_a_turn():
    """His pace carries him away from it: he turns, then runs from a standstill. Counted as if he could
    run any way at full pace at once, such touches looked safe, and most were lost (session 49)."""
    sim = sim_with((Side.LEFT, 9, 0.0, 0.0, 0.0))
    me = sim.world.player(Side.LEFT, 9)
    path, (bx, by), (vx, vy) = [], (-0.5, 0.0), (-0.78, 0.45)  # touched back at 150 degrees, out of reach at once
    for _ in range(skills.DODGE_LOOK):
        bx, by, vx, vy = bx + vx, by + vy, vx * 0.94, vy * 0.94
        path.append((bx, by))
    me.body = 180.0  # standing, facing the way it goes
    facing = skills._my_cycles(sim.world, me, path)
    me.body = 0.0  # standing, facing up the field: a turn first
    turning = skills._my_cycles(sim.world, me, path)
    assert facing <= skills.DODGE_LOOK and turning > facing
    me.vx = 0.8  # and running up the field: further off once turned
    assert skills._my_cycles(sim.world, me, path) >= turning


def test_a_new_dribble_lets_a_ball_rolling_its_way_run_unless_a_man_would_get_it_first():
    def first_command(*others):
        sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 30.0), *others)
        ball = sim.world.ball
        ball.x, ball.y, ball.vx, ball.vy = 0.5, 0.3, 0.8, 0.45  # pushed 30 degrees up by the last dribble
        skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10))
        return skill.step(sim.world, me).commands[0][0]

    # The new target (straight along x) is 30 degrees off the roll: the roll is kept, he runs after it.
    assert first_command() == "dash"
    # A man on that roll would have it first: the ball is touched onto another way.
    assert first_command((Side.RIGHT, 4, 4.0, 2.5, 180.0)) == "kick"


def test_a_new_dribble_takes_a_fast_ball_coming_by_under_control_instead_of_chasing_it():
    # A pass arrives at his feet, rolling the dribble's way but faster than he runs: let run, it
    # would run away from him (on rcssserver, over the touch line).
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0))
    ball = sim.world.ball
    ball.x, ball.y, ball.vx, ball.vy = 0.5, 0.0, 1.4, 0.0
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10))
    first = skill.step(sim.world, me).commands[0]
    assert first[0] == "kick"
    sim.command(Side.LEFT, 10, *first)
    sim.step()
    assert math.hypot(ball.vx, ball.vy) < 1.2  # the touch took pace off it
    for _ in range(30):
        for cmd in skill.step(sim.world, me).commands:
            sim.command(Side.LEFT, 10, cmd[0], *cmd[1:])
        sim.step()
        assert distance(me.x, me.y, ball.x, ball.y) < 3.0  # still his ball


def test_a_dribble_with_a_man_near_keeps_the_ball_within_reach_every_cycle():
    """Pushed metres ahead as in open space, the ball is loose for cycles, and a man pressing has it
    first; with one near, each touch lays it just in front of where the dribbler will be."""
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0), (Side.RIGHT, 4, 3.0, 3.0, -90.0))
    ball = sim.world.ball
    ball.x = 0.6
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("dribble", ":target (AbsolutePositioning :x 15 :y 0)", 10))
    furthest, kinds = 0.0, []
    for _ in range(12):
        cycle(sim, skill, me, kinds)
        furthest = max(furthest, distance(me.x, me.y, ball.x, ball.y))
    assert furthest <= sim.world.params.kickable_distance  # never out of his reach
    assert kinds.count("kick") >= 4 and "dash" in kinds  # touched again and again, running on between
    assert me.x > 4.0  # and it went on towards the target


def test_hold_ball_keeps_the_ball_in_reach_on_the_side_away_from_the_man_near():
    # An opponent stands 1.6 m to my left with the ball between us (within his reach): the touches
    # take it round to my right and keep it there; when he moves round to my right, over to my left.
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0), (Side.RIGHT, 4, 0.0, 1.6, -90.0))
    ball, him = sim.world.ball, sim.world.player(Side.RIGHT, 4)
    ball.x, ball.y = 0.0, 0.6
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("holdBall", number=10))
    kickable = sim.world.params.kickable_distance

    def hold(cycles):
        away = []
        for _ in range(cycles):
            step = skill.step(sim.world, me)
            assert step.status == "running"
            for cmd in step.commands:
                sim.command(Side.LEFT, 10, cmd[0], *cmd[1:])
            sim.step()
            assert distance(me.x, me.y, ball.x, ball.y) <= kickable  # never out of my reach
            away.append(distance(him.x, him.y, ball.x, ball.y))
        return away

    away = hold(15)
    assert away[-1] > 2.0 and ball.y < me.y  # on my far side from him, out of his kickable reach
    assert distance(me.x, me.y, 0.0, 0.0) < 1.0  # and I stayed where I was
    him.x, him.y = me.x, me.y - 1.6
    away = hold(15)
    assert away[-1] > 2.0 and ball.y > me.y


def test_hold_ball_needs_the_ball_in_reach_and_fails_once_it_is_gone():
    sim = sim_with((Side.LEFT, 10, 0.0, 0.0, 0.0))
    sim.world.ball.x = 5.0
    with pytest.raises(SkillError):
        skill_of(sim, Side.LEFT, 10, exec_("holdBall", number=10))
    sim.world.ball.x = 0.6
    skill, me = skill_of(sim, Side.LEFT, 10, exec_("holdBall", number=10))
    assert skill.step(sim.world, me).status == "running"
    sim.world.ball.x, sim.world.ball.vx = 3.0, 1.0  # knocked away
    assert skill.step(sim.world, me).status == "failed"
