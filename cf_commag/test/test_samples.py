"""Packing ACL messages into inbox samples and reading them back."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from cf_commag.transport.samples import SAMPLE_MAX_BYTES, SAMPLE_MAX_MESSAGES, pack_lines, sample_messages
from cf_lang import acl
from cf_lang.acl import AclMessage, AgentId, Performative


def test_small_bursts_go_out_as_one_sample_in_order():
    texts = [f'(inform :content "{i}")' for i in range(10)]
    samples = list(pack_lines(texts))
    assert len(samples) == 1
    assert sample_messages(samples[0]) == texts


def test_samples_respect_the_message_and_byte_limits():
    many = [f'(inform :content "{i}")' for i in range(SAMPLE_MAX_MESSAGES * 2 + 5)]
    samples = list(pack_lines(many))
    assert [len(sample_messages(s)) for s in samples] == [SAMPLE_MAX_MESSAGES, SAMPLE_MAX_MESSAGES, 5]
    big = ['(inform :content "' + "x" * (SAMPLE_MAX_BYTES // 3) + '")' for _ in range(7)]
    samples = list(pack_lines(big))
    assert all(len(s) <= SAMPLE_MAX_BYTES for s in samples) and len(samples) == 4
    assert [m for s in samples for m in sample_messages(s)] == big
    huge = ["y" * (SAMPLE_MAX_BYTES * 2)]  # one message larger than a sample still goes, alone
    assert list(pack_lines(huge)) == huge


def test_a_single_message_and_blank_lines():
    assert sample_messages('(inform :content "a")') == ['(inform :content "a")']
    assert sample_messages('(inform :content "a")\n\n  \n(inform :content "b")\n') == [
        '(inform :content "a")',
        '(inform :content "b")',
    ]


@given(st.lists(st.text(max_size=40), min_size=1, max_size=40))
def test_any_content_survives_packing(contents):
    # The writer escapes newlines in strings, so every message stays on its line.
    messages = [AclMessage(Performative.INFORM, sender=AgentId("a"), content=c) for c in contents]
    texts = [acl.to_text(m) for m in messages]
    back = [acl.parse(t) for s in pack_lines(texts) for t in sample_messages(s)]
    assert back == messages
