"""Agents hosted in one process: each its own agent, delivered to in-process, reachable over DDS as before."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest
from std_msgs.msg import String
from test_client import start_commag

from cf_commag.client import Agent, inbox_topic
from cf_commag.host import Host
from cf_commag.process import HOST_KEY, PID_KEY


def hosted(ros, host, name, cls, commag, **kw):
    return Agent(ros.node(name), name=name, service_class=cls, commag=commag, lease=2.0, host=host, **kw)


def inbox_samples(ros, name):
    """Every DDS sample that reaches ``name``'s inbox topic."""
    seen = []
    ros.node(f"watch_{name}").create_subscription(String, inbox_topic(name), seen.append, 100)
    return seen


def test_hosted_agents_talk_in_process_and_with_agents_elsewhere(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    host = Host(ros.node(f"host_{unique}"), name=f"players_{unique}", commag=commag)
    action = hosted(ros, host, f"action_{unique}", "Action", commag, team="blue", player_number=3)
    decision = hosted(ros, host, f"decision_{unique}", "PlayerDecision", commag, team="blue", player_number=3)
    outsider = Agent(ros.node(f"coach_{unique}"), name=f"coach_{unique}", service_class="Coaching", commag=commag)
    action.serve("fipa-request", lambda msg, responder: "(done)")
    outsider.serve("fipa-query", lambda msg, responder: "(Game :time 7)")
    on_dds = inbox_samples(ros, action.me.name)
    ros.spin_until(lambda: action.registered and decision.registered and outsider.registered, what="registration")

    # Each hosted agent is registered on its own, names its host and process, and is found by lookup.
    ros.spin_until(lambda: decision.provider("Kick", team="blue", player_number=3), what="lookup cache")
    entry = decision.providers("Action", team="blue", player_number=3)[0]
    meta = dict(entry.record.metadata)
    assert meta[HOST_KEY] == f"players_{unique}" and meta[PID_KEY].isdigit()

    # In the same process: delivered without a DDS sample, the full conversation still runs.
    delivered = host.delivered
    future = decision.request(action.me.name, "(exec Player kick :playerNumber 3 :whichTeam our :power 50)")
    ros.spin_until(future.done, what="answer in-process")
    assert future.result().ok and future.result().content == "(done)"
    assert host.delivered - delivered == 2  # the request and its inform
    ros.spin_for(0.3)
    assert on_dds == []

    # To and from an agent of another host (another process, as far as they know): over DDS.
    future = decision.request(outsider.me.name, "(val Game time)", protocol="fipa-query")
    ros.spin_until(future.done, what="answer over DDS")
    assert future.result().content == "(Game :time 7)"
    future = outsider.request(action.me.name, "(exec Player kick :playerNumber 3 :whichTeam our :power 50)")
    ros.spin_until(future.done, what="request over DDS to a hosted agent")
    assert future.result().ok
    ros.spin_until(lambda: on_dds, what="the request on the hosted agent's inbox topic")


def test_a_message_between_hosted_agents_is_handled_after_the_callback_that_sent_it(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    host = Host(ros.node(f"host_{unique}"), name=f"h_{unique}", commag=commag)
    first = hosted(ros, host, f"first_{unique}", "Action", commag)
    second = hosted(ros, host, f"second_{unique}", "Action", commag)
    order = []

    def relay(msg, responder):  # first, asked from outside, asks second before it answers
        order.append("first starts")
        second_future = first.request(second.me.name, "(val Game time)", protocol="fipa-query")
        second_future.add_done_callback(lambda f: responder.inform(f.result().content))
        order.append("first returns")

    def answer(msg, responder):
        order.append("second answers")
        return "(Game :time 3)"

    first.serve("fipa-query", relay)
    second.serve("fipa-query", answer)
    outsider = Agent(ros.node(f"out_{unique}"), name=f"out_{unique}", service_class="Coaching", commag=commag)
    ros.spin_until(lambda: first.registered and second.registered and outsider.registered, what="registration")
    future = outsider.request(first.me.name, "(val Game time)", protocol="fipa-query")
    ros.spin_until(future.done, what="the relayed answer")
    assert future.result().content == "(Game :time 3)"
    assert order == ["first starts", "first returns", "second answers"]


def test_a_host_holds_one_agent_per_name(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    host = Host(ros.node(f"host_{unique}"), name=f"h_{unique}", commag=commag)
    hosted(ros, host, f"twice_{unique}", "Action", commag)
    with pytest.raises(ValueError, match="already hosts"):
        hosted(ros, host, f"twice_{unique}", "Action", commag)
    with pytest.raises(ValueError, match="talks to"):
        Agent(ros.node(f"other_{unique}"), name=f"other_{unique}", service_class="Action", commag="/x", host=host)


HUNG = textwrap.dedent(
    """
    import time, rclpy
    from cf_commag.host import Host
    from cf_commag.runtime import default_executor
    rclpy.init()
    node = rclpy.create_node("hangs")
    host = Host(node, name="hangs", watchdog=1.0)
    node.create_timer(0.5, lambda: time.sleep(3600))  # a callback that never returns
    executor = default_executor(node)
    while True:
        executor.spin_once(timeout_sec=0.1)
    """
)


def test_a_host_whose_callbacks_hang_exits_so_that_it_is_relaunched():
    done = subprocess.run([sys.executable, "-c", HUNG], capture_output=True, text=True, timeout=60)
    assert done.returncode == 70
    assert "hung" in done.stderr + done.stdout
