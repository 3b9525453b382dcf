"""A decision component talks with its team-mates in ACL: it tells them the pass it asks for, and
sets off at once when a team-mate tells it a pass is coming.

The real decision component of blue 7 runs as a process; its perception, its action provider and
two team-mates' decision components are agents of the test, speaking the Framework Language over
DDS as any component would.
"""

from __future__ import annotations

import math

from cf_commag.agent import Agent
from cf_decision.talk import heard_pass
from cf_lang import Exec, parse_expr
from cf_lang.acl import AclMessage, AgentId, Performative
from cf_lang.expr import unparse
from cf_lang.ontology import AbsolutePositioning, Ball, Game, Heard, Player, PlayMode, Team, WorldState
from cf_lang.ontology import actions as act
from cf_sim_backend.services import PerceptionService
from cf_system import executable, start_commag


def at(x, y):
    return AbsolutePositioning(x=x, y=y, yaw=0.0)


def world(time, me, ball, mates):
    players = [Player(player_number=n, which_team=Team.OUR, positioning=at(*pos)) for n, pos in mates.items()]
    players.append(Player(player_number=1, which_team=Team.OPP, positioning=at(50.0, 0.0), is_goalie=True))
    return WorldState(
        time=time,
        me=Player(player_number=7, which_team=Team.OUR, positioning=at(*me)),
        ball=Ball(positioning=at(*ball)),
        players=tuple(players),
        game=Game(time=time, play_mode=PlayMode.PLAY_ON),
    )


def blue_7_services(probe, tag, common):
    """Blue 7's perception (the test publishes its WorldStates) and action provider (it agrees to
    every request and keeps it): the perception service and the list of requests."""
    perception = PerceptionService(
        Agent(probe.node, name=f"perception_{tag}", service_class="WorldModel", player_number=7, **common), "not yet"
    )
    requests = []

    def on_request(msg, responder):
        requests.append(parse_expr(msg.content))
        responder.agree()

    action = Agent(probe.node, name=f"action_{tag}", service_class="Action", player_number=7, **common)
    action.serve("fipa-request", on_request)
    return perception, requests


def off_line(p, a, b):
    """Distance of point p from the segment a-b."""
    ax, ay, bx, by = *a, *b
    t = max(0.0, min(1.0, ((p[0] - ax) * (bx - ax) + (p[1] - ay) * (by - ay)) / ((bx - ax) ** 2 + (by - ay) ** 2)))
    return math.hypot(p[0] - (ax + t * (bx - ax)), p[1] - (ay + t * (by - ay)))


def test_a_pass_is_told_to_team_mates_and_its_receiver_sets_off_before_the_ball_rolls(procs, probe, tag, tmp_path):
    team = f"blue{tag}"
    start_commag(procs, tag, tmp_path)
    procs.start(
        [
            executable("cf_decision", "decision"),
            "--ros-args",
            "-p",
            f"commag:=/commag_{tag}",
            "-p",
            f"team:={team}",
            "-p",
            "number:=7",
            "-p",
            "lease:=2.0",
            "-p",
            "log_requests:=true",
        ],
        "decision",
    )
    common = {"team": team, "commag": f"/commag_{tag}", "lease": 2.0}
    perception, requests = blue_7_services(probe, tag, common)
    heard = {4: [], 9: []}
    mates = {
        n: Agent(
            probe.node,
            name=f"mate{n}_{tag}",
            service_class="PlayerDecision",
            player_number=n,
            on_message=lambda msg, n=n: heard[n].append(msg),
            **common,
        )
        for n in heard
    }
    decision = f"{team}_7_decision"
    probe.wait_kind(decision, "registered", timeout=60)
    clock = iter(range(1, 10**6))

    def play(state_of, done, what, seconds=60.0):
        """Publish a perceived cycle every 0.1 s (mate 4 claiming the ball) until ``done()``; its value."""

        def cycle():
            perception.publish(state_of(next(clock)))
            claim = AclMessage(
                Performative.INFORM,
                receivers=(AgentId(decision),),
                content="(exec Player intercept :playerNumber 4 :whichTeam our)",
                user=(("X-eta", "0"),),
            )
            mates[4].send(claim)
            probe.spin_for(0.1)
            return done()

        return probe.spin_until(cycle, timeout=seconds, what=what)

    # 1. Mate 4 has the ball at (-30, 0); blue 7 stands at (-20, -10) and waits.
    here, ball = (-20.0, -10.0), (-30.0, 0.0)
    team_mates = {4: (-30.5, 0.0), 9: (10.0, 0.0)}
    play(lambda t: world(t, here, ball, team_mates), lambda: requests, "blue 7's first request")
    # 2. Mate 4 tells it it passes to blue 7: blue 7 runs to meet the ball on its way, still at mate
    # 4's feet in its perception.
    to_me = Exec(
        "Player",
        "pass",
        {"playerNumber": 4, "whichTeam": Team.OUR},
        act.Pass(to=Player(player_number=7, which_team=Team.OUR)),
    )
    told = AclMessage(Performative.INFORM, receivers=(AgentId(decision),), content=unparse(to_me))
    mates[4].send(told)

    def meeting():
        moves = [r.action for r in requests if isinstance(r, Exec) and r.method == "moveTo"]
        return next((m for m in moves if off_line((m.target.x, m.target.y), ball, here) < 1.0), None)

    meet = play(lambda t: world(t, here, ball, team_mates), meeting, "blue 7 to run to meet the pass")
    assert meet.target.x > here[0] - 10.0 and meet.speed == 100.0  # towards the ball, in a hurry
    # With log_requests its log says what the run was chosen on: the pass heard, mate 4's claim.
    logged = [line for line in procs.log("decision").splitlines() if "request t=" in line and "moveTo:" in line]
    run = [line for line in logged if " | passes 4>7@" in line]
    assert run and " | claims 4:0 | " in run[0], logged[-3:]
    assert " | (exec Player moveTo :playerNumber 7 :whichTeam our " in run[0], run[0]

    # Bad words from a team-mate are dropped, and blue 7 plays on.
    for content, user in (
        ("(exec Player intercept :playerNumber 99999 :whichTeam our)", (("X-eta", "0"),)),
        ("(exec Player intercept :playerNumber 4 :whichTeam our)", (("X-eta", "soon"),)),
        ("(exec Player pass :playerNumber 4 :whichTeam our :power 50)", ()),  # neither :to nor :target
        ("(exec Player pass :playerNumber 2.5 :whichTeam our :target (AbsolutePositioning :x 1 :y 2))", ()),
        ("(exec Player pass :playerNumber 4 ((((", ()),
        # Words that are no team-mate's: an opponent's, one without a player, one claiming blue 7.
        ("(WorldState :time 5 :me (Player :playerNumber 4 :whichTeam opp))", (("X-eta", "0"),)),
        ("(WorldState :time 5)", (("X-eta", "0"),)),
        (
            "(WorldState :time 5 :me (Player :playerNumber 7 :whichTeam our :positioning "
            "(AbsolutePositioning :x 40 :y 0)))",
            (("X-eta", "0"),),
        ),
    ):
        mates[4].send(AclMessage(Performative.INFORM, receivers=(AgentId(decision),), content=content, user=user))

    # 3a. Blue 7 tells the team-mates who may play the ball next (mate 4 claims it at once) where
    # it is (a WorldState: what one player perceives), its time to the ball riding on the word; a
    # team-mate far from the ball (mate 9, no claim) hears the time alone, in a plain claim.
    def own_word(n):
        words = [m for m in heard[n] if (m.content or "").startswith("(WorldState ")]
        return next((m for m in words if parse_expr(m.content).me.positioning.x == here[0]), None)

    word = play(lambda t: world(t, here, ball, team_mates), lambda: own_word(4), "blue 7 to tell where it is")
    assert parse_expr(word.content).me.player_number == 7 and int(dict(word.user)["X-eta"]) > 0
    assert not any((m.content or "").startswith("(WorldState ") for m in heard[9])
    plain = [m for m in heard[9] if m.content == "(exec Player intercept :playerNumber 7 :whichTeam our)"]
    assert plain and int(dict(plain[-1].user)["X-eta"]) > 0

    # 3b. Mate 9, 20 m up the field, tells blue 7 of an opponent in the lane between them that
    # blue 7 does not see: with the ball at its feet, blue 7 does not pass to mate 9.
    mine = (0.0, 0.0)
    free = {4: (-30.0, 0.0), 9: (20.0, 5.0)}
    cut = Player(player_number=5, which_team=Team.OPP, positioning=AbsolutePositioning(x=10.0, y=2.5, sigma_x=0.5))

    def cycle_with_word(t, ball_at):
        word = WorldState(
            time=t, me=Player(player_number=9, which_team=Team.OUR, positioning=at(*free[9])), players=(cut,)
        )
        told = AclMessage(
            Performative.INFORM, receivers=(AgentId(decision),), content=unparse(word), user=(("X-eta", "9"),)
        )
        mates[9].send(told)
        return world(t, mine, ball_at, free)

    for _ in range(3):  # (the word before the ball: an inform may overtake a perception)
        perception.publish(cycle_with_word(next(clock), (6.0, 0.0)))
        probe.spin_for(0.1)
    since = len(requests)

    def kicking():
        kinds = [r for r in requests[since:] if isinstance(r, Exec) and r.method in ("pass", "dribble", "shoot")]
        return kinds[-1] if kinds else None

    def to_mate_9(r):
        """A pass to mate 9's feet or to a point ahead of him (a through ball, 5-10 m)."""
        if r.method != "pass":
            return False
        a = r.action
        if a.to is not None:
            return a.to.player_number == 9
        return 19.0 <= a.target.x <= 31.0 and abs(a.target.y - 5.0) < 1.0

    played = play(lambda t: cycle_with_word(t, (0.5, 0.0)), kicking, "blue 7 to play the ball")
    assert not to_mate_9(played), played
    logged = [line for line in procs.log("decision").splitlines() if "request t=" in line]
    assert any(" | claims 4:0 9:9 | " in line for line in logged), logged[-3:]  # (mate 9's time, on its word)

    # 3c. Mate 9's word no longer holds that man: blue 7 passes to it, and tells
    # its team-mates; the text they get is the request the action provider got.
    after = len(heard[9])

    def told_pass():
        texts = [m for m in heard[9][after:] if (m.content or "").startswith("(exec Player pass :playerNumber 7")]
        return [m for m in texts if parse_expr(m.content) != played]  # (not 3b's kick into space)

    its_word = play(lambda t: world(t, mine, (0.5, 0.0), free), told_pass, "blue 7 to tell its pass")[0]
    passes = [r for r in requests if isinstance(r, Exec) and r.method == "pass"]
    assert passes, requests
    assert parse_expr(its_word.content) == passes[-1] and its_word.performative is Performative.INFORM
    assert to_mate_9(passes[-1]), passes[-1]  # (without the word, the pass 3b did not play)
    assert any((m.content or "").startswith("(exec Player pass :playerNumber 7") for m in heard[4])

    # 4. The ball on its way to mate 9, blue 7 (a midfielder) runs on up the field for it back,
    # at full speed: its own pass, kept as its team-mates keep it, tells it to.
    rolling_on, since = (6.0, 1.5), len(requests)

    def going():
        moves = [r.action for r in requests[since:] if isinstance(r, Exec) and r.method == "moveTo"]
        return next((m for m in moves if m.target.x >= mine[0] + 8.0 and m.speed == 100.0), None)

    play(lambda t: world(t, mine, rolling_on, free), going, "blue 7 to run on after its pass")
    logged = [line for line in procs.log("decision").splitlines() if "moveTo: pass and go" in line]
    assert logged and " | passes 4>7@" in logged[-1] and " 7>" in logged[-1], logged[-1:]


def test_with_talk_say_a_pass_goes_in_a_say_through_the_action_and_a_heard_one_is_met(procs, probe, tag, tmp_path):
    """``talk:=say`` (a competition's rules): blue 7 tells its team-mates nothing over the framework;
    it asks its action provider to say its pass, and meets a pass it hears of in its perception."""
    team = f"blue{tag}"
    start_commag(procs, tag, tmp_path)
    argv = [executable("cf_decision", "decision"), "--ros-args", "-p", f"commag:=/commag_{tag}", "-p", f"team:={team}"]
    procs.start([*argv, "-p", "number:=7", "-p", "lease:=2.0", "-p", "talk:=say"], "decision")
    common = {"team": team, "commag": f"/commag_{tag}", "lease": 2.0}
    perception, requests = blue_7_services(probe, tag, common)
    told = []
    mates = [
        Agent(
            probe.node,
            name=f"mate{n}_{tag}",
            service_class="PlayerDecision",
            player_number=n,
            on_message=told.append,
            **common,
        )
        for n in (4, 9)
    ]
    probe.wait_kind(f"{team}_7_decision", "registered", timeout=60)
    probe.spin_until(lambda: all(m.registered for m in mates), timeout=30, what="the team-mates' registration")
    clock = iter(range(1, 10**6))

    def play(state_of, done, what):
        def cycle():
            perception.publish(state_of(next(clock)))
            probe.spin_for(0.1)
            return done()

        return probe.spin_until(cycle, timeout=60.0, what=what)

    # 1. The ball at its feet, mate 9 free 20 m up: blue 7 passes, and says the pass first.
    mine, free = (0.0, 0.0), {4: (-30.0, 0.0), 9: (20.0, 5.0)}

    def said_and_passed():
        says = [r for r in requests if isinstance(r, Exec) and r.method == "say"]
        passes = [r for r in requests if isinstance(r, Exec) and r.method == "pass"]
        return (says, passes) if says and passes else None

    says, passes = play(lambda t: world(t, mine, (0.5, 0.0), free), said_and_passed, "blue 7 to say and pass")
    assert requests.index(says[0]) < requests.index(passes[0])  # said first: in synch mode the pass ends the cycle
    assert heard_pass(says[0].action.message) == passes[0].action, (says[0], passes[0])

    # 2. Mate 4 has the ball; blue 7 waits (mate 4 is nearer it, as blue 7 sees), until it hears mate
    # 4 say "p7": it runs to meet the ball on its way.
    here, ball, team_mates = (-20.0, -10.0), (-30.0, 0.0), {4: (-30.5, 0.0), 9: (10.0, 0.0)}
    since = len(requests)
    play(lambda t: world(t, here, ball, team_mates), lambda: len(requests) > since, "blue 7 to go on playing")
    assert not any(r.method == "intercept" for r in requests[since:] if isinstance(r, Exec))

    def with_word(t):
        state = world(t, here, ball, team_mates)
        return state.model_copy(update={"heard": (Heard(player_number=4, message="p7", time=t),)})

    def meeting():
        moves = [r.action for r in requests[since:] if isinstance(r, Exec) and r.method == "moveTo"]
        return next((m for m in moves if off_line((m.target.x, m.target.y), ball, here) < 1.0), None)

    meet = play(with_word, meeting, "blue 7 to run to meet the pass it heard of")
    assert meet.target.x > here[0] - 10.0 and meet.speed == 100.0

    # 3. Mate 4 says "n" (our set piece's taker may not touch the ball again): blue 7 goes for it.
    def not_mine(t):
        state = world(t, here, ball, team_mates)
        return state.model_copy(update={"heard": (Heard(player_number=4, message="n", time=t),)})

    since = len(requests)
    going = play(not_mine, lambda: any(r.method == "intercept" for r in requests[since:]), "blue 7 to go for the ball")
    assert going
    assert told == []  # no word over the framework: no claims, no sightings, no passes
