"""A site-specific MCE_R spectrum given as a table (pipeline/motions/site_specific.py,
`--target-spectrum CSV`): S_MS and S_M1 by ASCE 7-22 section 21.4 in closed form on the code's
own spectrum, the table read as written, a suite scaled to the table of the code's spectrum the
same as one scaled to its parameters, and a table the code cannot use refused in one line."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import engine
from pipeline.motions.code_suite import code_suite
from pipeline.motions.site_specific import read_target_table, site_specific_parameters
from pipeline.motions.target import asce7_target

S_MS, S_M1, T_L = 1.5, 0.9, 8.0


def _table(path, periods, sa_g, header="period_s,sa_g"):
    path.write_text(header + "\n" + "".join(f"{float(t)!r},{float(s)!r}\n"
                                            for t, s in zip(periods, sa_g, strict=True)))
    return path


def test_the_code_spectrum_gives_back_its_parameters_by_section_21_4():
    """On the two-period spectrum the largest Sa in 0.2-5 s is the plateau, S_MS (so 21.4's
    S_MS is 0.9 S_MS), and T Sa is S_M1 all along the 1/T branch (T_S = 0.6 s to T_L)."""
    s_ms, s_m1 = site_specific_parameters(asce7_target(S_MS, S_M1, T_L))
    assert s_ms == pytest.approx(0.9 * S_MS, rel=1e-12)
    assert s_m1 == pytest.approx(S_M1, rel=1e-12)


def test_a_peak_between_the_table_periods_is_not_invented(tmp_path):
    """A spectrum peaking at 1.5 s (T Sa = 1.5 x 0.8 = 1.2 g s there): S_M1 is its largest
    T Sa, at a table period; S_MS 0.9 x its largest Sa."""
    target = read_target_table(_table(tmp_path / "t.csv", [0.1, 0.2, 1.0, 1.5, 3.0, 6.0],
                                      [0.5, 0.6, 0.7, 0.8, 0.3, 0.1]))
    s_ms, s_m1 = site_specific_parameters(target)
    assert s_ms == pytest.approx(0.9 * 0.8, rel=1e-12)
    assert s_m1 == pytest.approx(1.5 * 0.8, rel=1e-12)
    assert "t.csv" in target.source and "sha256" in target.source
    assert target.level == "MCE_R" and target.component == "RotD100"


def test_a_suite_scaled_to_the_table_of_the_code_spectrum_is_the_code_suite(tmp_path):
    code = asce7_target(S_MS, S_M1, T_L)
    table = read_target_table(_table(tmp_path / "code.csv", code.periods, code.sa_g))
    rng = np.random.default_rng(5)
    pairs = [SimpleNamespace(accel=rng.normal(size=(800, 2)) * (1 + i), dt=0.01, name=f"p{i}",
                             event=f"e{i // 2}") for i in range(4)]
    names = [p.name for p in pairs]
    mapped = code_suite(pairs, names, engine.Building(), s_ms=S_MS, s_m1=S_M1, t_long=T_L)
    site = code_suite(pairs, names, engine.Building(), target=table)
    assert site.design.d_m == pytest.approx(mapped.design.d_m, rel=1e-12)  # S_M1 0.9 both
    np.testing.assert_allclose(site.factors, mapped.factors, rtol=1e-9)
    assert site.site["s_m1"] == pytest.approx(S_M1, rel=1e-12) and np.isnan(site.site["t_long"])


@pytest.mark.parametrize("header, periods, sa_g, said", [
    ("period,sa", [0.1, 6.0], [1.0, 0.1], r"needs the columns period_s \(s\) and sa_g \(g\)"),
    ("period_s,sa_g", [0.1, 2.0, 1.0, 6.0], [1.0, 0.5, 0.6, 0.1], "strictly increasing"),
    ("period_s,sa_g", [0.1, 1.0, 6.0], [1.0, -0.5, 0.1], "finite and > 0"),
    ("period_s,sa_g", [0.5, 1.0, 6.0], [1.0, 0.5, 0.1], "need 0.2 to 5 s at least"),
])
def test_a_table_the_code_cannot_use_is_refused_in_one_line(tmp_path, header, periods, sa_g,
                                                            said):
    with pytest.raises(ValueError, match=said) as caught:
        read_target_table(_table(tmp_path / "bad.csv", periods, sa_g, header))
    assert "\n" not in str(caught.value)
