"""Reader/writer: golden cases, round trips, limits and hostile input."""

from __future__ import annotations

import contextlib
import math
import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cf_lang import DEFAULT_LIMITS, Keyword, Limits, SexpError, SexpLimitError, SexpSyntaxError, Symbol, dumps, loads
from cf_lang.errors import SexpWriteError


def same(a, b) -> bool:
    """Equal and of the same types all the way down (Symbol == str is not enough)."""
    if type(a) is not type(b):
        return False
    if type(a) is list:
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
    return a == b


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("(a b)", [Symbol("a"), Symbol("b")]),
        ("(:x 1 -2 +3)", [Keyword("x"), 1, -2, 3]),
        ("(1.5 -2e-3 .5 5. 1E3)", [1.5, -0.002, 0.5, 5.0, 1000.0]),
        ('("a \\"q\\" \\\\ \\n\\t\\r" "")', ['a "q" \\ \n\t\r', ""]),
        ("(a ; comment (\n b)", [Symbol("a"), Symbol("b")]),
        ("((()))", [[[]]]),
        ("42", 42),
        ('  "x"  ', "x"),
        (
            "(- + ... a-b tcp://host:1 20261122T101010123Z 1abc)",
            [Symbol(s) for s in ["-", "+", "...", "a-b"]]
            + [Symbol("tcp://host:1"), Symbol("20261122T101010123Z"), Symbol("1abc")],
        ),
        ("(-inf nan 1_000)", [Symbol("-inf"), Symbol("nan"), Symbol("1_000")]),
        ('(é ü "日本")', [Symbol("é"), Symbol("ü"), "日本"]),
    ],
)
def test_golden(text, expected):
    assert same(loads(text), expected)


def test_bytes_input_and_keyword_forms():
    assert same(loads(b"(:x 1)"), [Keyword("x"), 1])
    assert Keyword("x") == Keyword(":x") == ":x"
    assert Keyword("x").name == "x"
    assert Symbol("Player").name == "Player"


def test_paper_examples_verbatim():
    text = "(exec Player turnToObject :playerNum 3\n:whichTeam our\n:obj (Player :playerNum 4 :whichTeam our))"
    value = loads(text)
    assert value[:3] == ["exec", "Player", "turnToObject"]
    assert same(value[-1], [Symbol("Player"), Keyword("playerNum"), 4, Keyword("whichTeam"), Symbol("our")])
    assert same(loads("(AbsolutePositioning :x 10.3 :y -23.67 :yaw 0.23456)")[2], 10.3)


@pytest.mark.parametrize(
    ("text", "cls", "line", "column", "found_part"),
    [
        ("(a", SexpSyntaxError, 1, 3, "end of input"),
        ("(a))", SexpSyntaxError, 1, 4, ")"),
        ('(a "b', SexpSyntaxError, 1, 4, "end of input"),
        ("(a)\n  b", SexpSyntaxError, 2, 3, "b"),
        ("", SexpSyntaxError, 1, 1, "end of input"),
        ('(\n"\\q")', SexpSyntaxError, 2, 2, "\\q"),
        ("(: a)", SexpSyntaxError, 1, 2, ":"),
        ("(1e999)", SexpSyntaxError, 1, 2, "1e999"),
        ("(" * 65 + ")" * 65, SexpLimitError, 1, 65, "("),
    ],
)
def test_errors_say_where(text, cls, line, column, found_part):
    with pytest.raises(cls) as info:
        loads(text)
    err = info.value
    assert (err.line, err.column) == (line, column)
    assert found_part in err.found
    assert err.expected
    assert f"line {line}, column {column}" in str(err)


def test_invalid_utf8_is_located():
    with pytest.raises(SexpSyntaxError) as info:
        loads(b"(a\n b \xff)")
    assert (info.value.line, info.value.column) == (2, 4)
    assert "0xff" in info.value.found


def test_limits():
    with pytest.raises(SexpLimitError, match="too large"):
        loads("(" + "a " * 10 + ")", limits=Limits(max_bytes=10))
    with pytest.raises(SexpLimitError, match="too many atoms"):
        loads("(" + "a " * 10 + ")", limits=Limits(max_atoms=5))
    with pytest.raises(SexpLimitError, match="nesting too deep"):
        loads("((((a))))", limits=Limits(max_depth=3))
    assert loads("((((a))))", limits=Limits(max_depth=4)) == [[[["a"]]]]
    # Integers of at most 4,000 digits (docs/language.md); Python alone would take 4,300.
    assert loads("-" + "7" * 4000) == -int("7" * 4000)
    for digits in (4001, 4300, 5000):
        with pytest.raises(SexpLimitError, match="integer too long"):
            loads("(n " + "7" * digits + ")")
    with pytest.raises(SexpLimitError, match="integer too long"):
        loads("1" * 5000)


def test_hundred_thousand_deep_and_oversized_are_refused():
    with pytest.raises(SexpLimitError):
        loads("(" * 100_000 + ")" * 100_000)
    with pytest.raises(SexpLimitError):
        loads("(" * 100_000, limits=Limits(max_bytes=1 << 21))
    with pytest.raises(SexpLimitError):
        loads("a " * (DEFAULT_LIMITS.max_bytes // 2 + 1))
    with pytest.raises(SexpLimitError):
        loads(b"x" * (DEFAULT_LIMITS.max_bytes + 1))


@settings(max_examples=300)
@given(st.binary(max_size=300))
def test_fuzzed_bytes_give_only_typed_errors(data):
    with contextlib.suppress(SexpError):
        loads(data)


@settings(max_examples=300)
@given(st.text(alphabet='()":;\\ \n\tab1.-+eE', max_size=80))
def test_fuzzed_text_near_the_grammar(data):
    with contextlib.suppress(SexpError):
        loads(data)


symbols = st.from_regex(r"[A-Za-z*!?<>=/_][A-Za-z0-9*!?<>=/_.:-]{0,10}", fullmatch=True).map(Symbol)
keywords = st.from_regex(r"[A-Za-z][A-Za-z0-9-]{0,10}", fullmatch=True).map(Keyword)
atoms = st.one_of(
    symbols,
    keywords,
    st.text(max_size=20),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.floats(allow_nan=False, allow_infinity=False),
)
values = st.recursive(atoms, lambda children: st.lists(children, max_size=6), max_leaves=40)


@settings(max_examples=400)
@given(values)
def test_round_trip_identity(value):
    assert same(loads(dumps(value)), value)


@given(st.lists(values, max_size=4))
def test_written_text_is_one_line(value):
    assert "\n" not in dumps(value)


@pytest.mark.parametrize("bad", [True, math.nan, math.inf, {"a": 1}, None, object()])
def test_writer_refuses_values_without_a_form(bad):
    with pytest.raises(SexpWriteError):
        dumps([bad])


@pytest.mark.parametrize("bad", ["", "a b", "(x", "12", ":x", '"q'])
def test_invalid_symbols_cannot_be_made(bad):
    with pytest.raises(SexpWriteError):
        Symbol(bad)


def test_writing_a_very_deep_value_is_a_typed_error():
    value: list = []
    for _ in range(100_000):
        value = [value]
    with pytest.raises(SexpWriteError):
        dumps(value)


def test_cf_lang_imports_without_ros():
    code = (
        "import sys, cf_lang, cf_lang.protocols, cf_lang.expr; print(any(m.startswith('rclpy') for m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize("pad", ["", " ", "\n", " \t\n ", "; trailing comment\n"])
def test_both_tokenizer_paths_accept_surrounding_space(pad):
    # Text with a backslash or a ';' takes the regex path; other text the split path.
    assert same(loads(f'{pad}(a "q\\"" b){pad}'), [Symbol("a"), 'q"', Symbol("b")])
    assert same(loads(f"{pad}(a b){pad}"), [Symbol("a"), Symbol("b")])


@settings(max_examples=200)
@given(values, st.sampled_from(["", " ", "\n", "\t \n"]))
def test_round_trip_with_padding(value, pad):
    assert same(loads(pad + dumps(value) + pad), value)
