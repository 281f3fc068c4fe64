"""The settings as cpp/include/gauss/settings.h declares them, read from the header itself, so that the
tests which check the module against them need no list of their own: a setting added to the header is
checked everywhere at once."""
import re

from conftest import REPO

HEADER = REPO / "cpp" / "include" / "gauss" / "settings.h"
# inline constexpr Setting lambda{"lam", "lambda", 4.0, 0.0, 1e4, false, ...
_DECLARATION = re.compile(r'inline constexpr (Setting|Option|Choice)\s+\w+\s*\{\s*"(\w+)"(?:,\s*"([^"]*)")?'
                          r'(?:,\s*[^,]+,\s*[^,]+,\s*[^,]+,\s*(true|false))?')


def declared():
    """{python name: (kind, label, integer)}: kind 'Setting', 'Option' or 'Choice'; label (in messages)
    and integer only for a Setting."""
    out = {}
    for kind, name, label, integer in _DECLARATION.findall(HEADER.read_text()):
        out[name] = (kind, label if kind == "Setting" else None, integer == "true")
    return out


def names(kind):
    return tuple(name for name, (k, _, _) in declared().items() if k == kind)
