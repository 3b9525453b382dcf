"""docs/language.md: every example parses, and the vocabulary section matches the code."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from cf_lang import acl, parse_expr
from cf_lang.acl import Performative
from cf_lang.vocabulary import BEGIN, END, render

SPEC = Path(__file__).resolve().parents[2] / "docs" / "language.md"
EXAMPLES = re.findall(r"```cf\n(.*?)```", SPEC.read_text(encoding="utf-8"), re.DOTALL)
MESSAGE_HEADS = {p.value for p in Performative}


def test_spec_has_examples():
    assert len(EXAMPLES) >= 8


@pytest.mark.parametrize("example", EXAMPLES)
def test_every_example_is_valid(example):
    head = example.lstrip("(").split(None, 1)[0].lower()
    if head in MESSAGE_HEADS:
        msg = acl.parse(example)
        if msg.performative in (Performative.REQUEST, Performative.QUERY_REF, Performative.INFORM):
            parse_expr(msg.content)
    else:
        parse_expr(example)


def test_vocabulary_section_is_generated_from_the_code():
    text = SPEC.read_text(encoding="utf-8")
    section = text[text.index(BEGIN) : text.index(END) + len(END)] + "\n"
    assert section == render(), "docs/language.md is stale: regenerate it with python -m cf_lang.vocabulary"
