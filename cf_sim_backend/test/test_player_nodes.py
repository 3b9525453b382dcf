"""A player's nodes in-process with the simulator and a ComMAg, in one rclpy context.

Perception, action and decision of one player (each its own node and agent), the embedded
simulator and the ComMAg: the decision subscribes to the perception, asks the action component,
and the player moves in the simulated world.
"""

from __future__ import annotations

import pytest
from rclpy.parameter import Parameter

from cf_commag.client import Agent
from cf_commag.commag_node import CommagNode
from cf_decision.decision_node import DecisionNode
from cf_lang import parse_expr
from cf_sim_backend.embedded.action_node import ActionNode
from cf_sim_backend.embedded.perception_node import PerceptionNode
from cf_sim_backend.embedded.sim_node import SimNode
from cf_sim_backend.world import Side


def params(**values):
    return [Parameter(k, value=v) for k, v in values.items()]


def start_commag(ros, unique, tmp_path) -> str:
    """An active ComMAg in this process; its name."""
    node = ros.add(
        CommagNode(
            node_name=f"commag_{unique}",
            context=ros.context,
            parameter_overrides=params(autostart=False, persistence_path=str(tmp_path / "registry.json")),
        )
    )
    node.trigger_configure()
    node.trigger_activate()
    return f"/commag_{unique}"


def test_one_player_plays_through_its_three_components(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    # In one test process there is no command that starts a component again: nothing to relaunch.
    common = {"commag": commag, "team": f"blue{unique}", "number": 2, "relaunch": False}
    sim = ros.add(
        SimNode(
            context=ros.context,
            parameter_overrides=params(
                sim=f"sim_{unique}",
                commag=commag,
                relaunch=False,
                left_size=2,
                right_size=0,
                cycle_period=0.05,
                auto_kick_off_cycles=3,
            ),
        )
    )
    player = {"sim": f"sim_{unique}", "side": "l", **common}
    perception = ros.add(PerceptionNode(context=ros.context, parameter_overrides=params(**player)))
    action = ros.add(ActionNode(context=ros.context, parameter_overrides=params(**player)))
    decision = ros.add(DecisionNode(context=ros.context, parameter_overrides=params(team_size=2, **common)))

    # Each node is named after its agent.
    assert [n.get_name() for n in (perception, action, decision)] == [
        f"blue{unique}_2_perception",
        f"blue{unique}_2_action",
        f"blue{unique}_2_decision",
    ]
    ros.spin_until(lambda: all(a.agent.registered for a in (perception, action, decision)), what="registration")
    start = sim.sim.world.player(Side.LEFT, 2)
    x0, y0 = start.x, start.y

    def moved() -> bool:
        now = sim.sim.world.player(Side.LEFT, 2)
        return abs(now.x - x0) + abs(now.y - y0) > 1.0

    ros.spin_until(moved, timeout=60, what="the player to move (a field player goes for the ball)")
    ros.spin_until(lambda: decision.requests.stats.done >= 1, timeout=60, what="a request done")
    assert decision.perception == f"blue{unique}_2_perception"
    assert action.agent.counters["received"] >= 1 and perception.perception.subscribers


def test_invalid_parameters_are_refused_with_the_parameter_named(ros):
    with pytest.raises(ValueError, match="number"):
        DecisionNode(context=ros.context, parameter_overrides=params(number=12))
    with pytest.raises(ValueError, match="side"):
        PerceptionNode(context=ros.context, parameter_overrides=params(side="x"))


def test_a_say_asked_for_in_acl_is_heard_by_a_team_mate_and_the_running_action_goes_on(ros, unique, tmp_path):
    """``(exec Player say ...)`` over the wire: heard in a team-mate's perceived WorldState (``:heard``),
    beside a ``moveTo`` in force, which it neither replaces nor ends; a say rcssserver would not carry
    is refused with why."""
    commag = start_commag(ros, unique, tmp_path)
    team = f"blue{unique}"
    sim_name = f"sim_{unique}"
    ros.add(
        SimNode(
            context=ros.context,
            parameter_overrides=params(
                sim=sim_name, commag=commag, relaunch=False, left_size=3, right_size=0, cycle_period=0.05
            ),
        )
    )
    common = {"commag": commag, "team": team, "relaunch": False, "sim": sim_name, "side": "l"}
    speaker = ros.add(ActionNode(context=ros.context, parameter_overrides=params(number=2, **common)))
    listener = ros.add(PerceptionNode(context=ros.context, parameter_overrides=params(number=3, **common)))
    client = Agent(ros.node(f"client_{unique}"), name=f"client_{unique}", service_class="Coaching", commag=commag)
    ros.spin_until(lambda: speaker.agent.registered and listener.agent.registered and client.registered)

    heard = []

    def on_state(msg):
        state = parse_expr(msg.content)
        heard.extend((h.player_number, h.message) for h in state.heard)

    client.request(
        listener.agent.me.name, "(val WorldState)", protocol="fipa-subscribe", timeout=60.0, on_update=on_state
    )
    key = ":playerNumber 2 :whichTeam our"
    moving = client.request(
        speaker.agent.me.name, f"(exec Player moveTo {key} :target (AbsolutePositioning :x -40 :y 30))"
    )
    said = client.request(speaker.agent.me.name, f'(exec Player say {key} :message "t0725310")')
    ros.spin_until(said.done, what="the say's answer")
    assert said.result().ok and said.result().content == "(done say :cycles 0)"
    ros.spin_until(lambda: (2, "t0725310") in heard, timeout=30, what="team-mate 3 to hear it")
    assert not moving.done() and speaker.action.active  # the run goes on
    refused = client.request(speaker.agent.me.name, f'(exec Player say {key} :message "far too long")')
    ros.spin_until(refused.done, what="the long say's answer")
    assert refused.result().state == "refused" and "a say carries 1 to 10 characters" in refused.result().content
