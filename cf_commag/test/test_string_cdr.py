"""Inbox samples in serialized form: byte for byte what rclpy's own serializer makes and reads."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rclpy.serialization import deserialize_message, serialize_message
from std_msgs.msg import String

from cf_commag.transport.cdr import from_cdr, to_cdr
from cf_commag.transport.outbox import sample_text


@settings(max_examples=500)
@given(st.text(max_size=300))
def test_the_same_bytes_as_rclpy_both_ways(text):
    assert to_cdr(text) == serialize_message(String(data=text))
    sample = serialize_message(String(data=text))
    assert from_cdr(sample) == deserialize_message(sample, String).data


def test_big_endian_and_invalid_utf8_are_read_like_rclpy():
    big = b"\x00\x00\x00\x00\x00\x00\x00\x05ab\xffc\x00"
    assert from_cdr(big) == "ab\ufffdc" == deserialize_message(big, String).data


@pytest.mark.parametrize(
    "sample", [b"\x00\x07\x00\x00\x02\x00\x00\x00a\x00", b"\x00\x01\x00\x00\x09\x00\x00\x00ab", b""]
)
def test_what_it_cannot_read_is_a_value_error(sample):
    with pytest.raises(ValueError):
        from_cdr(sample)


def test_another_encapsulation_goes_to_rclpy():
    # An encapsulation this module does not read is handed to rclpy's reader.
    sample = serialize_message(String(data="(inform)"))
    assert sample_text(sample) == "(inform)"
    with pytest.raises(ValueError):
        from_cdr(b"\x00\x07" + sample[2:])
