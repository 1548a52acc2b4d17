"""`LinkageMotion.slides` is keyed by the slide's name ("3", "23", "E") and also answers to
its symbol as the reports, CSVs and docs write it ("s3", "s23", "sE"); issue 33 §3."""

import pickle

import numpy as np
import pytest

from mechcli.core.linkage import DriverMotion, guide_bar, slider_crank, solve


def test_a_slide_answers_to_its_name_and_to_its_symbol():
    m = solve(slider_crank(0.1, 0.3, 0.0, 1), {1: DriverMotion(np.array([0.0]))}, order=1)
    assert list(m.slides) == ["3"]                   # iteration: the names, as before
    assert m.slides["s3"] is m.slides["3"]
    assert "s3" in m.slides and "3" in m.slides and "s4" not in m.slides
    # by hand at θ1 = 0: s3 = r + l = 0.4 m
    assert float(m.slides["s3"].s[0]) == pytest.approx(0.4, rel=1e-15)
    assert m.slides.get("s9") is None
    with pytest.raises(KeyError):
        m.slides["s9"]
    g = solve(guide_bar(0.1, 0.3, 0.0, 1), {1: DriverMotion(np.array([0.5]))}, order=0)
    assert g.slides["s23"] is g.slides["23"]
    assert pickle.loads(pickle.dumps(m.slides))["s3"].s[0] == m.slides["3"].s[0]
