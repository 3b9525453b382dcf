"""When a decision goes out as a request, and what its answer means."""

from __future__ import annotations

from cf_decision.receive import Announced
from cf_decision.requests import ActionRequests, RequestStats, aim_text, request_text, same_action
from cf_decision.situation import Decision
from cf_lang.ontology import AbsolutePositioning, Ball, Game, Player, Team, Velocity, WorldState
from cf_lang.ontology import actions as act


def move(x, y, speed=70.0):
    return act.MoveTo(target=AbsolutePositioning(x=x, y=y), speed=speed)


def test_same_action_within_tolerances():
    assert same_action(move(10.0, 5.0), move(10.4, 5.3))
    assert not same_action(move(10.0, 5.0), move(11.5, 5.0))
    assert not same_action(move(10.0, 5.0), move(10.0, 5.0, speed=100.0))
    assert same_action(act.Turn(angle=3.1), act.Turn(angle=-3.1))  # the same way round the circle
    assert not same_action(act.Turn(angle=0.0), act.Turn(angle=0.3))
    assert same_action(
        act.Dribble(target=AbsolutePositioning(x=1, y=1), speed=70),
        act.Dribble(target=AbsolutePositioning(x=1.2, y=0.9), speed=72),
    )
    assert not same_action(act.Intercept(), act.TurnToObject(obj=Ball()))
    assert same_action(act.TurnToObject(obj=Ball()), act.TurnToObject(obj=Ball()))


def test_the_failure_of_a_replaced_request_does_not_resend_the_current_one():
    tracker = ActionRequests()
    first, second = object(), object()
    assert tracker.wants("moveTo", move(0, 0))
    tracker.sent("moveTo", move(0, 0), first)
    assert tracker.wants("moveTo", move(20, 0))  # changed: replaces the first
    tracker.sent("moveTo", move(20, 0), second)
    tracker.answered(first, ok=False)  # "replaced by a newer request"
    assert not tracker.wants("moveTo", move(20.3, 0.2))  # the second still runs
    assert tracker.stats.replaced == 1 and tracker.stats.failed == 0 and tracker.stats.requests == 2


def test_an_unchanged_decision_is_sent_again_only_after_its_request_ended():
    tracker = ActionRequests()
    token = object()
    tracker.sent("turn", act.Turn(angle=1.0), token)
    assert not tracker.wants("turn", act.Turn(angle=1.0))
    tracker.answered(token, ok=False)  # the request in force failed: try again
    assert tracker.wants("turn", act.Turn(angle=1.0))
    tracker.sent("turn", act.Turn(angle=1.0), object())
    assert tracker.stats.resends == 1 and tracker.stats.failed == 1 and tracker.stats.cycles == 2
    assert "1.00 per cycle" in tracker.stats.line()


def test_choices_with_the_ball_are_counted_by_reason_without_their_numbers():
    stats = RequestStats()
    for why in (
        "forward pass to team-mate 9",
        "forward pass to team-mate 10",
        "fastest to a contested ball (3 cycles): win it",
    ):
        stats.chose(why)
    assert stats.choices == {"forward pass to team-mate": 2, "fastest to a contested ball: win it": 1}
    assert stats.line().endswith("with the ball: forward pass to team-mate 2, fastest to a contested ball: win it 1")


def test_the_log_line_of_a_kick_carries_its_aim_and_the_ball_and_opponents_as_believed():
    def opp(x, y, sigma):
        return Player(which_team=Team.OPP, positioning=AbsolutePositioning(x=x, y=y, sigma_x=sigma, sigma_y=sigma))

    players = (opp(-30.0, 2.0, 0.4), opp(-20.0, -10.0, 3.3), opp(10.0, 0.0, 0.1))  # the last over 30 m away
    ball = Ball(positioning=AbsolutePositioning(x=-35.24, y=4.1))
    state = WorldState(time=5, ball=ball, players=players, game=Game(time=5))
    clear = Decision("pass", act.Pass(target=AbsolutePositioning(x=-12.0, y=25.0), power=100.0), "clear the ball")
    assert aim_text(state, clear) == " @ target -12.0 25.0 ball -35.2 4.1 opp -30.0 2.0 0.4, -20.0 -10.0 3.3"
    assert aim_text(state, Decision("intercept", act.Intercept(), "fastest")) == ""  # no target point
    assert aim_text(WorldState(time=5, game=Game(time=5)), clear) == ""  # no ball believed


def test_a_logged_request_tells_what_it_was_chosen_on():
    me = Player(player_number=7, which_team=Team.OUR, positioning=AbsolutePositioning(x=-10.04, y=3.0))
    ball = Ball(positioning=AbsolutePositioning(x=-12.0, y=2.5), velocity=Velocity(vx=8.0, vy=-1.0), age=1)
    their = [Player(which_team=Team.OPP, positioning=AbsolutePositioning(x=x, y=0.0)) for x in (50.0, 21.04, 30.0)]
    state = WorldState(time=40, me=me, ball=ball, game=Game(time=40), players=their)
    to_me = act.Pass(to=Player(player_number=7, which_team=Team.OUR))
    to_point = act.Pass(target=AbsolutePositioning(x=5.0, y=5.0))
    passes = [
        Announced(4, to_me, AbsolutePositioning(x=-20.0, y=0.0), 31),
        Announced(6, to_point, AbsolutePositioning(x=-5.0, y=0.0), 35),
        Announced(2, to_me, AbsolutePositioning(x=-30.0, y=0.0), 12),  # long rolled past: not awaited
    ]
    run = Decision("moveTo", move(-11.0, 2.0, 100.0), "meet the pass")
    line = request_text(state, run, {9: 3, 4: 12}, passes, "(exec Player moveTo ...)")
    assert line == (
        "request t=40 moveTo: meet the pass | me -10.0 3.0 | ball -12.0 2.5 v 8.0 -1.0 age 1 | line 30.0"
        " | claims 4:12 9:3 | passes 4>7@31 6>pt@35 | (exec Player moveTo ...)"
    )
    still = ball.model_copy(update={"velocity": Velocity(vx=-0.01, vy=0.0)})
    assert "v 0.0 0.0 age" in request_text(state.model_copy(update={"ball": still}), run, {}, [], "(exec)")  # no -0.0
    blind = request_text(WorldState(time=3, game=Game(time=3)), run, {}, [], "(exec)")
    assert blind == "request t=3 moveTo: meet the pass | me ? | ball ? | line ? | claims  | passes  | (exec)"
    alone = state.model_copy(update={"players": their[:1]})  # one opponent known: the line cannot be told
    assert "age 1 | line ? | claims" in request_text(alone, run, {}, [], "(exec)")
