"""Code comments, docstrings and docs link the section of docs/ that holds a figure
(docs/performance.md#the-guards-cost): every such link must name a heading that exists, or the figure
it points to is lost the day the section is renamed."""
import re

from conftest import REPO

LINK = re.compile(r"docs/([\w-]+\.md)#([\w-]+)")
RELATIVE = re.compile(r"\]\(([\w-]+\.md)#([\w-]+)\)")  # a docs page's link to another docs page
ROOTS = ("cpp", "python_addon", "scripts", "tests", "farm", "blender_scenes", "docs", "README.md")
KINDS = (".h", ".cpp", ".py", ".sh", ".md", ".js", ".yaml", ".txt")


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def anchors(doc):
    text = (REPO / "docs" / doc).read_text(encoding="utf-8")
    return {slug(line.lstrip("#")) for line in text.splitlines() if re.match(r"#{1,6} ", line)}


def sources():
    for root in ROOTS:
        path = REPO / root
        for file in ([path] if path.is_file() else sorted(path.rglob("*"))):
            if file.is_file() and file.suffix in KINDS:
                yield file


def test_every_link_to_a_docs_section_names_a_heading():
    known, broken = {}, []
    for file in sources():
        text = file.read_text(encoding="utf-8", errors="replace")
        links = LINK.findall(text) + (RELATIVE.findall(text) if file.parent == REPO / "docs" else [])
        for doc, anchor in links:
            if doc not in known:
                known[doc] = anchors(doc) if (REPO / "docs" / doc).is_file() else set()
            if anchor not in known[doc]:
                broken.append("%s: docs/%s#%s" % (file.relative_to(REPO), doc, anchor))
    assert broken == [], "\n".join(broken)


def test_the_slug_is_githubs():
    assert slug(" The guard's cost") == "the-guards-cost"
    assert slug("Figures behind the code's choices") == "figures-behind-the-codes-choices"
    assert slug("Set-up at scale") == "set-up-at-scale"
