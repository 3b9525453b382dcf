"""FIPA-ACL: golden string forms, round trips, parameters, checks."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cf_lang import AclError, SexpError
from cf_lang.acl import (
    AclMessage,
    AgentId,
    Performative,
    check_content,
    format_datetime,
    parse,
    parse_datetime,
    to_sexp,
    to_text,
)
from cf_lang.sexp import dumps

GOLDEN = (
    "(request :sender (agent-identifier :name blue_3_decision :addresses (sequence tcp://10.0.0.3:7001))"
    " :receiver (set (agent-identifier :name blue_3_action))"
    ' :content "(exec Player kick :playerNumber 3 :whichTeam our :power 80 :direction 0.1)"'
    " :language cf-lang :ontology robocup-soccer :protocol fipa-request"
    ' :conversation-id c42 :reply-with r1 :reply-by 20261122T101010123Z :X-team "blue")'
)


def test_golden_message_reads_and_writes_back_identically():
    msg = parse(GOLDEN)
    assert msg.performative is Performative.REQUEST
    assert msg.sender == AgentId("blue_3_decision", ("tcp://10.0.0.3:7001",))
    assert msg.receivers == (AgentId("blue_3_action"),)
    assert msg.content.startswith("(exec Player kick")
    assert msg.conversation_id == "c42" and msg.reply_with == "r1"
    assert msg.reply_by == pytest.approx(parse_datetime("20261122T101010123Z"))
    assert msg.user == (("X-team", "blue"),)
    assert to_text(msg) == GOLDEN


def test_all_22_performatives_case_insensitive():
    assert len(Performative) == 22
    for perf in Performative:
        assert parse(f'({perf.value.upper()} :content "x")').performative is perf


def test_leniencies_for_foreign_agents():
    msg = parse("(inform :sender alice :receiver bob :content (Game :time 3) :conversation-id 17)")
    assert msg.sender == AgentId("alice") and msg.receivers == (AgentId("bob"),)
    assert msg.content == "(Game :time 3)"
    assert msg.conversation_id == "17"


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ('(shout :content "x")', "unknown performative"),
        ("(inform :colour red)", "unknown message parameter"),
        ("(inform :sender (agent-identifier :addresses (sequence a)))", "without :name"),
        ("(inform :reply-by tomorrow)", "date-time"),
        ("(inform :reply-by 20261341T101010123Z)", "not a valid date-time"),
        ("(inform :content)", "pairs"),
        ('(inform :content "a" :content "b")', "given twice"),
        ("inform", r"expected \(performative"),
    ],
)
def test_bad_messages(text, words):
    with pytest.raises(AclError, match=words):
        parse(text)


def test_malformed_text_is_a_sexp_error():
    with pytest.raises(SexpError):
        parse('(inform :content "x"')


def test_datetimes():
    assert format_datetime(0) == "19700101T000000000Z"
    assert parse_datetime("19700101T000001500Z") == 1.5
    assert parse_datetime(format_datetime(1_795_000_000.25)) == pytest.approx(1_795_000_000.25)


def test_check_content():
    check_content(AclMessage(Performative.INFORM))
    with pytest.raises(AclError, match="language"):
        check_content(AclMessage(Performative.INFORM, language="fipa-sl"))
    with pytest.raises(AclError, match="ontology"):
        check_content(AclMessage(Performative.INFORM, ontology="music"))


def test_reply_keeps_the_conversation():
    msg = parse(GOLDEN)
    reply = msg.reply(Performative.AGREE)
    assert reply.receivers == (msg.sender,) and reply.conversation_id == "c42" and reply.in_reply_to == "r1"


names = st.from_regex(r"[a-z][a-z0-9_@.]{0,12}", fullmatch=True)
texts = st.text(min_size=1, max_size=30).filter(lambda s: s.strip())
messages = st.builds(
    AclMessage,
    performative=st.sampled_from(Performative),
    sender=st.builds(AgentId, names, st.tuples() | st.tuples(texts)),
    receivers=st.lists(st.builds(AgentId, names, st.just(())), min_size=1, max_size=3).map(tuple),
    content=st.none() | st.text(max_size=60),
    protocol=st.none() | st.sampled_from(["fipa-request", "fipa-query", "fipa-subscribe"]),
    conversation_id=st.none() | texts,
    reply_with=st.none() | texts,
    in_reply_to=st.none() | texts,
    reply_by=st.none() | st.integers(0, 4_000_000_000_000).map(lambda ms: ms / 1000),
    reply_to=st.lists(st.builds(AgentId, names, st.just(())), max_size=2).map(tuple),
    language=st.none() | st.just("cf-lang"),
    encoding=st.none() | texts,
    ontology=st.none() | st.just("robocup-soccer"),
    user=st.lists(
        st.tuples(st.from_regex(r"X-[a-z]{1,8}", fullmatch=True), texts), max_size=2, unique_by=lambda p: p[0].lower()
    ).map(tuple),
)


@settings(max_examples=300)
@given(messages)
def test_generated_messages_round_trip(msg):
    assert parse(to_text(msg)) == msg


@settings(max_examples=300)
@given(messages, st.none() | st.builds(AgentId, names, st.just(())))
def test_the_direct_writer_writes_what_the_general_one_does(msg, default_sender):
    assert to_text(msg, sender=default_sender) == dumps(to_sexp(msg, sender=default_sender))


def test_to_text_writes_a_default_sender_only_when_the_message_has_none():
    me, other = AgentId("me"), AgentId("other")
    anonymous = AclMessage(Performative.INFORM, receivers=(other,), content="(x)")
    assert parse(to_text(anonymous, sender=me)).sender == me
    assert parse(to_text(anonymous)).sender is None
    signed = anonymous.with_(sender=other)
    assert parse(to_text(signed, sender=me)).sender == other
