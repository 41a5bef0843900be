"""``B@4``, the point of link 4 under B, as a value: made and read in one place (``scene.link_point``)."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from kinepoly.scene.link_point import SEPARATOR, LinkPoint, point_of

_NAMES = st.text(st.characters(blacklist_characters=SEPARATOR, blacklist_categories=("Cs",)), min_size=1, max_size=6)


@given(_NAMES, st.none() | st.text(max_size=6))
def test_a_link_point_reads_back_from_its_text(point: str, link: str | None) -> None:
    named = LinkPoint(point, link)
    assert LinkPoint.parse(named.text) == named and str(named) == named.text
    assert point_of(named.text) == point and named.text == point + named.at_link


def test_the_textbook_names() -> None:
    assert LinkPoint.parse("B@4") == LinkPoint("B", "4") and LinkPoint("B", "4").text == "B@4"
    assert LinkPoint.parse("B0") == LinkPoint("B0") and LinkPoint("B0").at_link == ""
    assert LinkPoint.parse("B@") == LinkPoint("B", "")  # an empty link name is kept, for the scene's check to refuse
