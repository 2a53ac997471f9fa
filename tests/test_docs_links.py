"""The README's and docs/' relative links lead somewhere: the file exists and, for a link
with ``#anchor`` into a Markdown page, a heading of that page has that anchor (GitHub's rule:
lower case, punctuation but ``-`` and ``_`` dropped, spaces as ``-``)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LINK = re.compile(r"\]\(([^)\s]+)\)")
FENCE = re.compile(r"^(```|~~~)")


def anchor(heading: str) -> str:
    """GitHub's anchor of a Markdown heading's text."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    out: set[str] = set()
    fenced = False
    for line in page.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            fenced = not fenced
        elif not fenced and line.startswith("#"):
            out.add(anchor(line.lstrip("#")))
    return out


def links(page: Path) -> list[tuple[int, str]]:
    out = []
    for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
        out += [(number, m.group(1)) for m in LINK.finditer(line)
                if not m.group(1).startswith(("http://", "https://", "mailto:"))]
    return out


def test_anchor_follows_githubs_rule():
    assert anchor(" Hidden anchors: likelihoods, not a gate") == \
        "hidden-anchors-likelihoods-not-a-gate"
    assert anchor("Columns in C (`prolog/ddc/batch/c/ddc_columns.c`)") == \
        "columns-in-c-prologddcbatchcddc_columnsc"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_relative_links_lead_somewhere(page: Path):
    broken = []
    for number, link in links(page):
        path, _, fragment = link.partition("#")
        target = (page.parent / path).resolve() if path else page
        if not target.exists():
            broken.append(f"{page.name}:{number}: {link}: no such file")
        elif fragment and target.suffix == ".md" and fragment not in anchors(target):
            broken.append(f"{page.name}:{number}: {link}: no heading with that anchor")
    assert not broken, "\n".join(broken)
