"""The agent runtime in-process: registration, conversations over real DDS, lookup cache, failover."""

from __future__ import annotations

import pytest
from rclpy.parameter import Parameter
from std_msgs.msg import String

from cf_commag.client import Agent, Failure, Refuse, inbox_topic
from cf_commag.commag_node import CommagNode


def start_commag(ros, unique, tmp_path):
    node = CommagNode(
        node_name=f"commag_{unique}",
        context=ros.context,
        parameter_overrides=[
            Parameter("autostart", value=False),
            Parameter("persistence_path", value=str(tmp_path / "registry.json")),
        ],
    )
    ros.add(node)
    node.trigger_configure()
    node.trigger_activate()
    return f"/commag_{unique}"


def agent(ros, name, cls, commag, **kw):
    node = ros.node(name)
    return Agent(node, name=name, service_class=cls, commag=commag, lease=2.0, **kw)


def test_agents_register_find_each_other_and_talk(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    action = agent(ros, f"action_{unique}", "Action", commag, team="blue", player_number=3)
    decision = agent(ros, f"decision_{unique}", "PlayerDecision", commag, team="blue", player_number=3)
    served = []

    def on_request(msg, responder):
        served.append(msg.content)
        responder.agree()
        return "(done)"

    def on_query(msg, responder):
        if "Game" not in msg.content:
            raise Refuse("only Game is known here")
        return "(Game :time 42)"

    action.serve("fipa-request", on_request)
    action.serve("fipa-query", on_query)
    ros.spin_until(lambda: action.registered and decision.registered, what="registration")

    # The cache, fed by the latched snapshot, finds a provider by taxonomy (Kick -> Action).
    ros.spin_until(lambda: decision.provider("Kick", team="blue", player_number=3), what="lookup cache")
    assert decision.provider("Kick", team="blue", player_number=3) == action.me.name
    assert decision.provider("Kick", team="red") is None

    updates = []
    future = decision.request(
        action.me.name,
        "(exec Player kick :playerNumber 3 :whichTeam our :power 50 :direction 0)",
        on_update=updates.append,
    )
    ros.spin_until(future.done, what="request answer")
    reply = future.result()
    assert reply.ok and reply.content == "(done)" and [u.performative.value for u in updates] == ["agree"]
    assert served and served[0].startswith("(exec Player kick")

    future = decision.request(action.me.name, "(val Game time)", protocol="fipa-query")
    ros.spin_until(future.done)
    assert future.result().ok and future.result().content == "(Game :time 42)"

    future = decision.request(action.me.name, "(val Ball positioning)", protocol="fipa-query")
    ros.spin_until(future.done)
    assert future.result().state == "refused" and "only Game is known here" in future.result().content

    # Authoritative lookup straight from the ComMAg.
    answer = decision.lookup("Kick", team="blue")
    ros.spin_until(answer.done)
    assert [p.name for p in answer.result().providers] == [action.me.name]


def test_failure_timeout_and_unserved_protocol(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    server = agent(ros, f"server_{unique}", "Action", commag)
    client = agent(ros, f"client_{unique}", "PlayerDecision", commag)

    def broken(msg, responder):
        raise Failure("the ball is not kickable")

    server.serve("fipa-request", broken)
    ros.spin_until(lambda: server.registered and client.registered)
    future = client.request(server.me.name, "(exec Player kick)")
    ros.spin_until(future.done)
    assert future.result().state == "failed" and "not kickable" in future.result().content

    future = client.request(server.me.name, "(val Game time)", protocol="fipa-query")
    ros.spin_until(future.done)
    assert future.result().state == "refused" and "does not serve fipa-query" in future.result().content

    with pytest.raises(ValueError, match="not an agent name"):
        client.request(None, "(exec Player kick)")  # e.g. a lookup that found no provider
    future = client.request("nobody_home", "(exec Player kick)", timeout=0.3)
    ros.spin_until(future.done)
    assert future.result().state == "timed-out" and future.result().message is None


def test_subscription_informs_until_cancelled(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    perception = agent(ros, f"perception_{unique}", "WorldModel", commag)
    decision = agent(ros, f"decision_{unique}", "PlayerDecision", commag)
    subscribers = []
    cancelled = []

    def on_subscribe(msg, responder):
        responder.agree()
        responder.on_cancel = lambda: cancelled.append(True)
        subscribers.append(responder)

    perception.serve("fipa-subscribe", on_subscribe)
    tick = {"n": 0}

    def publish():
        tick["n"] += 1
        for responder in list(subscribers):
            if responder.open:
                responder.inform(f"(Game :time {tick['n']})")

    perception.node.create_timer(0.02, publish)
    informs = []
    future = decision.request(
        perception.me.name, "(val WorldState)", protocol="fipa-subscribe", on_update=lambda m: informs.append(m.content)
    )
    ros.spin_until(lambda: len(informs) >= 6, what="6 informs")
    decision.cancel(future)
    ros.spin_until(future.done, what="cancel confirmed")
    assert future.result().state == "cancelled"
    # An update already on its way when we cancelled closes the conversation on our side (see
    # protocols.SUBSCRIBE), maybe before the perception has read the cancel: on a loaded machine
    # it had not yet. It does read it, once.
    ros.spin_until(lambda: cancelled, what="the perception told of the cancel")
    ros.spin_for(0.2)
    assert cancelled == [True]
    assert informs[0] is None or informs[0].startswith("(Game")  # the agree carries no content


def test_bad_input_never_stops_an_agent(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    server = agent(ros, f"server_{unique}", "Action", commag)
    server.serve("fipa-request", lambda msg, responder: "(ok)")
    raw = ros.node(f"raw_{unique}")
    pub = raw.create_publisher(String, inbox_topic(server.me.name), 10)
    ros.spin_until(lambda: raw.count_subscribers(inbox_topic(server.me.name)) > 0)
    for garbage in ["(((", "\x00\xff", '(shout :content "x")', '(inform :content "x")', "(" * 100000]:
        pub.publish(String(data=garbage))
    ros.spin_until(lambda: server.counters["received"] >= 5, what="garbage delivered")
    assert server.counters["bad"] >= 3
    client = agent(ros, f"client_{unique}", "PlayerDecision", commag)
    ros.spin_until(lambda: client.registered)
    future = client.request(server.me.name, "(exec Player kick)")
    ros.spin_until(future.done)
    assert future.result().ok


def test_failover_to_redundant_provider(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    first = agent(ros, f"a_first_{unique}", "Action", commag, team="blue", player_number=5)
    second = agent(ros, f"b_second_{unique}", "Action", commag, team="blue", player_number=5)
    user = agent(ros, f"user_{unique}", "PlayerDecision", commag)
    ros.spin_until(lambda: first.registered and second.registered)
    ros.spin_until(lambda: len(user.providers("Dribble", team="blue", player_number=5)) == 2, what="both cached")
    assert user.provider("Dribble", team="blue", player_number=5) == first.me.name
    done = first.close()
    ros.spin_until(done.done, what="deregistration")
    ros.spin_until(lambda: user.provider("Dribble", team="blue", player_number=5) == second.me.name, what="failover")


def test_a_sample_may_carry_several_messages(ros, unique, tmp_path):
    commag = start_commag(ros, unique, tmp_path)
    server = agent(ros, f"server_{unique}", "Action", commag)
    seen = []
    server.serve("fipa-request", lambda msg, responder: seen.append(msg.content) or "(ok)")
    raw = ros.node(f"raw_{unique}")
    pub = raw.create_publisher(String, inbox_topic(server.me.name), 10)
    answers = []
    raw.create_subscription(String, inbox_topic(f"raw_{unique}"), answers.append, 10)
    ros.spin_until(lambda: raw.count_subscribers(inbox_topic(server.me.name)) > 0)
    requests = [
        f'(request :sender raw_{unique} :receiver {server.me.name} :content "(exec Player kick :power {i})" '
        f":protocol fipa-request :conversation-id c{i})"
        for i in range(3)
    ]
    # Three requests and a bad line in one sample: the bad one is counted, the others served.
    pub.publish(String(data="\n".join([requests[0], "(((", *requests[1:]])))
    # A foreign sender's single message written over several lines still reads as one.
    # (Only the conversation id changes: the names carry a random suffix that may hold "c0" too.)
    again = requests[0].replace(" :content", "\n  :content").replace(":conversation-id c0)", ":conversation-id c9)")
    pub.publish(String(data=again))
    ros.spin_until(lambda: len(seen) == 4, what="all requests served")
    assert seen == [f"(exec Player kick :power {i})" for i in (0, 1, 2, 0)]
    assert server.counters["bad"] == 1
    # The three answers of the batch went back to us together, as one sample.
    ros.spin_until(lambda: sum(len(a.data.split("\n")) for a in answers) >= 4, what="answers")
    assert len(answers[0].data.split("\n")) == 3


def test_reply_by_on_the_wire_is_todays_date_and_the_timeout_still_works(ros, unique, tmp_path):
    """What a FIPA peer reads: the request text on the receiver's inbox carries a wall-clock :reply-by."""
    import re
    import time

    from cf_lang.acl import parse_datetime

    commag = start_commag(ros, unique, tmp_path)
    asker = agent(ros, f"asker_{unique}", "PlayerDecision", commag)
    peer = ros.node(f"peer_{unique}")  # a plain reader of the inbox: it never answers
    seen: list[str] = []
    from cf_commag.transport.qos import INBOX_QOS

    peer.create_subscription(String, inbox_topic(f"silent_{unique}"), lambda m: seen.append(m.data), INBOX_QOS)
    sent_at = time.time()
    future = asker.request(f"silent_{unique}", "(val Game time)", protocol="fipa-query", timeout=1.5)
    ros.spin_until(lambda: seen, what="the request on the wire")
    stamp = re.search(r":reply-by (\S+?)\)?(\s|$)", seen[0])
    assert stamp, seen[0]
    reply_by = parse_datetime(stamp.group(1).rstrip(")"))
    assert sent_at + 1.0 < reply_by < time.time() + 2.0, (seen[0], sent_at)
    ros.spin_until(future.done, timeout=10, what="the timeout")
    assert future.result().state == "timed-out"
