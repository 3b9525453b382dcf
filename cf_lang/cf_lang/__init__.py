"""cf_lang: the Common Framework's language, as a plain Python library (no ROS).

from cf_lang import loads, dumps          # S-expressions, like json
from cf_lang import parse_expr, unparse    # instances, val, exec
from cf_lang import acl, protocols, ontology, taxonomy
"""

from . import acl, ontology, protocols, taxonomy
from .errors import (
    AclError,
    ExpressionError,
    LanguageError,
    ProtocolError,
    SexpError,
    SexpLimitError,
    SexpSyntaxError,
    SexpWriteError,
)
from .expr import Exec, Val, unparse
from .expr import parse as parse_expr
from .ontology import LANGUAGE, ONTOLOGY
from .sexp import DEFAULT_LIMITS, Keyword, Limits, Symbol, dumps, loads

__all__ = [
    "DEFAULT_LIMITS",
    "LANGUAGE",
    "ONTOLOGY",
    "AclError",
    "Exec",
    "ExpressionError",
    "Keyword",
    "LanguageError",
    "Limits",
    "ProtocolError",
    "SexpError",
    "SexpLimitError",
    "SexpSyntaxError",
    "SexpWriteError",
    "Symbol",
    "Val",
    "acl",
    "dumps",
    "loads",
    "ontology",
    "parse_expr",
    "protocols",
    "taxonomy",
    "unparse",
]
