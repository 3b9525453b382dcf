"""Conversation protocols: both sides of request, query and subscribe, with a fake clock."""

from __future__ import annotations

import pytest

from cf_lang import ProtocolError
from cf_lang.acl import AgentId, Performative, format_datetime, parse, to_text
from cf_lang.protocols import ConversationTable, initiate, not_understood, respond

ME, PEER = AgentId("decision"), AgentId("action")


def wire(msg):
    """Send through the string form, as on the real transport."""
    return parse(to_text(msg))


def test_request_agree_inform():
    conv, request = initiate("fipa-request", me=ME, peer=PEER, content="(exec ...)", now=0.0, wall=0.0, timeout=1.0)
    assert request.performative is Performative.REQUEST and request.reply_by == 1.0
    server = respond(wire(request), me=PEER, now=0.1)
    assert conv.receive(wire(server.send("agree", now=0.1)), now=0.1) == "agreed"
    assert conv.receive(wire(server.send("inform", "(done)", now=0.2)), now=0.2) == "done"
    assert conv.finished and server.finished


@pytest.mark.parametrize(("answer", "state"), [("refuse", "refused"), ("failure", "failed"), ("inform", "done")])
def test_request_direct_answers(answer, state):
    conv, request = initiate("fipa-request", me=ME, peer=PEER, content="x", now=0.0)
    server = respond(wire(request), me=PEER, now=0.0)
    assert conv.receive(wire(server.send(answer, "(r)", now=0.0)), now=0.0) == state


def test_responder_cannot_answer_twice_or_out_of_order():
    _conv, request = initiate("fipa-request", me=ME, peer=PEER, content="x", now=0.0)
    server = respond(wire(request), me=PEER, now=0.0)
    server.send("agree", now=0.0)
    with pytest.raises(ProtocolError, match="cannot send agree in state agreed"):
        server.send("agree", now=0.0)
    server.send("inform", now=0.0)
    with pytest.raises(ProtocolError, match="conversation is over"):
        server.send("failure", now=0.0)


def test_initiator_rejects_unexpected_messages():
    conv, request = initiate("fipa-request", me=ME, peer=PEER, content="x", now=0.0)
    server = respond(wire(request), me=PEER, now=0.0)
    wrong = server.send("agree", now=0.0).with_(performative=Performative.SUBSCRIBE)
    with pytest.raises(ProtocolError):
        conv.receive(wrong, now=0.0)
    stray = server.send("inform", now=0.0).with_(in_reply_to="nothing")
    with pytest.raises(ProtocolError, match="answers nothing we sent"):
        conv.receive(stray, now=0.0)


def test_timeout_from_reply_by():
    conv, _ = initiate("fipa-request", me=ME, peer=PEER, content="x", now=10.0, wall=10.0, timeout=0.5)
    assert not conv.expired(10.4)
    assert conv.expired(10.6) and conv.state == "timed-out"


def test_reply_by_is_wall_clock_while_the_deadline_is_on_the_callers_clock():
    # A monotonic clock reads seconds since boot; on the wire that would be a date in 1970.
    conv, request = initiate("fipa-request", me=ME, peer=PEER, content="x", now=5.0, wall=1_795_000_000.0, timeout=2.0)
    assert request.reply_by == 1_795_000_002.0
    assert format_datetime(request.reply_by).startswith("2026")
    assert "2026" in to_text(request).split(":reply-by ")[1][:4]
    assert not conv.expired(6.9)
    assert conv.expired(7.1)


def test_a_timeout_without_the_wall_clock_is_refused():
    with pytest.raises(ValueError, match="wall"):
        initiate("fipa-request", me=ME, peer=PEER, content="x", now=5.0, timeout=2.0)


def test_query():
    conv, query = initiate("fipa-query", me=ME, peer=PEER, content="(val Game time)", now=0.0)
    assert query.performative is Performative.QUERY_REF
    server = respond(wire(query), me=PEER, now=0.0)
    assert conv.receive(wire(server.send("inform", "(Game :time 4)", now=0.0)), now=0.0) == "done"


def test_subscribe_inform_repeatedly_then_cancel():
    conv, sub = initiate("fipa-subscribe", me=ME, peer=PEER, content="(val WorldState)", now=0.0, wall=0.0, timeout=1)
    server = respond(wire(sub), me=PEER, now=0.0)
    assert conv.receive(wire(server.send("agree", now=0.0)), now=0.0) == "subscribed"
    for t in range(5):
        assert conv.receive(wire(server.send("inform", f"({t})", now=t)), now=t) == "subscribed"
    assert not conv.expired(100.0)  # an agreed subscription waits for nothing
    cancel = conv.send("cancel", now=6.0)
    assert server.receive(wire(cancel), now=6.0) == "cancelling"
    assert conv.receive(wire(server.send("inform", now=6.0)), now=6.0) == "cancelled"


def test_table_correlates_and_expires():
    table = ConversationTable()
    a, _req_a = initiate("fipa-request", me=ME, peer=PEER, content="a", now=0.0, wall=0.0, timeout=1.0)
    b, req_b = initiate("fipa-request", me=ME, peer=PEER, content="b", now=0.0, wall=0.0, timeout=5.0)
    table.add(a)
    table.add(b)
    server_b = respond(wire(req_b), me=PEER, now=0.0)
    assert table.dispatch(wire(server_b.send("inform", now=0.1)), now=0.1) is b
    assert len(table) == 1
    assert table.expire(2.0) == [a] and len(table) == 0
    with pytest.raises(ProtocolError, match="no open conversation"):
        table.dispatch(wire(server_b.history[-1]), now=3.0)


def test_not_understood_reply():
    msg = parse('(inform :sender (agent-identifier :name x) :content "?" :conversation-id c9 :reply-with r3)')
    answer = not_understood(msg, "no such conversation", me=ME)
    assert answer.performative is Performative.NOT_UNDERSTOOD
    assert answer.receivers == (AgentId("x"),) and answer.in_reply_to == "r3"
    assert "no such conversation" in answer.content


def test_respond_needs_an_opening_message():
    with pytest.raises(ProtocolError):
        respond(parse("(inform :sender x :conversation-id c)"), me=PEER, now=0.0)
    with pytest.raises(ProtocolError, match="conversation-id"):
        respond(parse('(request :sender x :content "y")'), me=PEER, now=0.0)
