"""A player's nodes in-process with the simulator and a ComMAg, in one rclpy context.

Perception, action and decision of one player (each its own node and agent), the embedded
simulator and the ComMAg: the decision subscribes to the perception, asks the action component,
and the player moves in the simulated world.
"""

from __future__ import annotations

import pytest
from rclpy.parameter import Parameter

from cf_commag.commag_node import CommagNode
from cf_decision.decision_node import DecisionNode
from cf_sim_backend.embedded.action_node import ActionNode
from cf_sim_backend.embedded.perception_node import PerceptionNode
from cf_sim_backend.embedded.sim_node import SimNode
from cf_sim_backend.world import Side


def params(**values):
    return [Parameter(k, value=v) for k, v in values.items()]


def test_one_player_plays_through_its_three_components(ros, unique, tmp_path):
    commag = f"/commag_{unique}"
    node = ros.add(
        CommagNode(
            node_name=f"commag_{unique}",
            context=ros.context,
            parameter_overrides=params(autostart=False, persistence_path=str(tmp_path / "registry.json")),
        )
    )
    node.trigger_configure()
    node.trigger_activate()
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
