"""Avoid Self-Intersections' cost is stated once, measured, in docs/performance.md ("The guard's cost");
every other place that speaks of it (the README, the setting's tooltip, the solver's docstring) points
there and gives no figure of its own, so a new measurement changes one sentence (issue 26: the tooltip,
the README and the solver had three different figures)."""
import re

from conftest import REPO

SECTION = "### The guard's cost"
ANCHOR = "docs/performance.md#the-guards-cost"
FIGURE = re.compile(r"\d+(\.\d+)?\s*(x|\u00d7|times)\b|\btwice\b|\btwo to\b|\bone more step\b|\ba step's time\b",
                    re.IGNORECASE)

# (file, a phrase that starts the place where it speaks of the cost, how it points to the section)
PLACES = (
    ("README.md", "**Avoid Self-Intersections** (off by default)", ANCHOR),
    ("python_addon/gauss_stylization/settings/schema.py", 'Bool("avoid_self_intersections"', "The guard's cost"),
    ("cpp/python/iteration_bindings.h", 'cls.def_property("avoid_self_intersections"', "The guard's cost"),
)


def _paragraph(text, start):
    """From ``start`` to the next blank line or list item."""
    at = text.index(start)
    end = min([i for i in (text.find("\n\n", at), text.find("\n- ", at)) if i >= 0] or [len(text)])
    return text[at:end]


def test_the_performance_notes_state_one_measured_figure():
    text = (REPO / "docs" / "performance.md").read_text(encoding="utf-8")
    assert text.count(SECTION) == 1
    statement = text[text.index(SECTION) + len(SECTION):].strip().split("\n\n")[0]
    figures = re.findall(r"\*\*[^*]*?(\d+(?:\.\d+)?) times[^*]*\*\*", statement)
    assert len(figures) == 1, statement  # one number, in bold, for the lead to update


def test_every_other_place_points_to_it_without_a_figure_of_its_own():
    for name, start, pointer in PLACES:
        place = _paragraph((REPO / name).read_text(encoding="utf-8"), start)
        assert pointer in place, (name, place)
        assert not FIGURE.search(place), (name, FIGURE.search(place).group(0))
