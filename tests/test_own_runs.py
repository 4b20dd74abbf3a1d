"""A user's own runs: figure, summary, repr, report, -F/G explained, the reference default.

The plants here are a user's, not the paper's: a DC motor's shaft angle driven by a
voltage (with names and units), and a pendulum whose friction uses a comparison
(so its ``-F/G`` cannot be computed with jets).
"""

from __future__ import annotations

import json
import math
import sys
import warnings

import famcc
import matplotlib.image as mpimg
import numpy as np
import pytest
from famcc import plot, verdicts
from famcc.simulation import SimResult

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

# DC motor: angle x1 [rad], speed x2 [rad/s], voltage u [V].
# J x2' = (K/R) u - (b + K^2/R) x2 - load sin t
J, B, K, R = 0.01, 0.1, 0.05, 1.0


def motor(x0=(0.0, 0.0)):
    return famcc.plants.StrictFeedback(
        g=[lambda x, t: 1.0, lambda x, t: K / (R * J)],
        f=[
            lambda x, t: 0.0,
            lambda x, t: -(B + K * K / R) / J * x[1] - 0.5 / J * 0.01 * np.sin(t),
        ],
        x0=list(x0),
        name="dc-motor",
        output=("angle", "rad"),
        input=("voltage", "V"),
    )


def motor_controller(k_u=2.0, dt=1e-3):
    return famcc.Controller(
        2, dt, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral", eps=0.02, k_u=k_u
    )


def motor_run(k_u=2.0, t_end=4.0, limits=(-3.0, 3.0)):
    return famcc.simulate(
        motor(), motor_controller(k_u), t_end, reference=famcc.Constant(1.0), u_limits=limits
    )


def pendulum():
    """Coulomb friction written with a comparison: fine on floats, not on jets."""

    def friction(x, t):
        return -0.3 if x[1] > 0 else 0.3

    return famcc.plants.StrictFeedback(
        g=[lambda x, t: 1.0, lambda x, t: 4.0],
        f=[lambda x, t: 0.0, lambda x, t: -9.81 * np.sin(x[0]) + friction(x, t)],
        x0=[0.4, 0.0],
        name="pendulum",
        output=("angle", "rad"),
        input=("torque", "N m"),
    )


@pytest.fixture(scope="module")
def run():
    return motor_run()


# -- the figure ------------------------------------------------------------------------------


def test_figure_of_a_user_plant_uses_their_names_and_units(run, tmp_path):
    fig = run.plot()
    titles = [ax.get_title() for ax in fig.axes]
    assert [t[:4] for t in titles] == ["(a) ", "(b) ", "(c) ", "(d) ", "(e) "]
    assert "angle" in titles[0] and "voltage" in titles[3]
    labels = [ax.get_ylabel() for ax in fig.axes]
    # one quantity per line, each with its unit
    assert labels[0].split("\n") == ["$z_{1}$ [rad]", "$z_{2}$ [rad/s]"]
    assert labels[1] == "$z_{1}$ [rad]"
    assert labels[2] == "$s_{fn}$ [rad]"  # LaMC at order 2: the offset is in z1's unit
    assert labels[3] == "voltage $u$ [V]"
    assert labels[4].split("\n") == [r"nominal $\xi$ [-]", r"flexible $\tilde\xi$ [-]"]
    assert all(ax.get_xlabel() == "time [s]" for ax in fig.axes)
    assert "[y]" not in " ".join(labels) and "input units" not in " ".join(labels)
    # the one-line note in plain words fits the figure's width
    note = fig._supxlabel
    assert "LaMC: lateral constraint" in note.get_text() and "\n" not in note.get_text()
    renderer = fig.canvas.get_renderer()
    assert note.get_window_extent(renderer).width <= fig.bbox.width
    # every panel draws data, and the PNG is a real picture
    for ax in fig.axes:
        assert any(np.isfinite(line.get_ydata()).any() for line in ax.get_lines())
    path = plot.save(fig, tmp_path / "motor.png")
    assert path.read_bytes()[:8] == PNG_MAGIC
    img = mpimg.imread(path)
    assert img.shape[0] >= 900 and img.shape[1] == 1200
    assert float(np.std(img[..., :3])) > 0.05


def test_figure_panels_window_and_eps(run):
    fig = run.plot(["input", "accuracy"], window=(1.0, 3.0), eps=0.05)
    assert [ax.get_title()[:4] for ax in fig.axes] == ["(a) ", "(b) "]
    for ax in fig.axes:
        assert ax.get_xlim() == pytest.approx((1.0, 3.0), abs=1e-3)
    band = [line for line in fig.axes[1].get_lines() if "epsilon" in str(line.get_label())]
    assert band and float(band[0].get_ydata()[0]) == 0.05
    with pytest.raises(ValueError, match="unknown panel"):
        run.plot(["nope"])
    with pytest.raises(ValueError, match="window"):
        run.plot(window=(3.0, 1.0))
    blind = famcc.simulate(
        motor(), motor_controller(), 0.5, reference=famcc.Constant(1.0), record=False
    )
    assert plot.panels_of(blind) == ["error", "accuracy", "input"]
    with pytest.raises(ValueError, match="record=True"):
        blind.plot(["constraint"])


def test_reproduce_figures_are_the_general_panels_plus_the_paper_extras():
    sc = famcc.scenarios.paper("finite-time")
    res = sc.run(t_end=2.0)
    paper_fig = plot.scenario_figure(sc, res)
    own_fig = res.plot()
    paper = [ax.get_title()[4:] for ax in paper_fig.axes]
    own = [ax.get_title()[4:] for ax in own_fig.axes]
    assert len(paper) == 7 and len(own) == 5
    # the general panels appear in the paper's figure with the same content
    for title in own:
        assert title in paper
    assert plot.scenario_panels(3)[-2:] == ["input", "xi"] and "stage" in plot.scenario_panels(3)


# -- summary, repr, rich views, data frame -------------------------------------------------


def test_repr_is_a_few_lines_without_arrays(run):
    text = repr(run)
    lines = text.splitlines()
    assert 3 <= len(lines) <= 5
    assert "array(" not in text and "[0." not in text
    assert "output angle [rad], input voltage [V]" in lines[0]
    assert "LaMC" in lines[1] and "Constant(1.0)" in lines[1]
    assert "settled to |z1| < 0.02 rad" in text


def test_summary_numbers_against_an_independent_computation(run):
    s = run.summary()
    assert s["eps"] == 0.02  # the controller's preset accuracy (LaMC, order 2)
    t, z1, u, v = run.t, run.z[:, 0], run.u, run.v
    outside = [k for k in range(len(t)) if not abs(z1[k]) < 0.02]
    ts = float(t[outside[-1] + 1])
    tail = t >= ts
    lo, hi = run.u_limits
    sat = (v < lo) | (v > hi)
    expanded = np.any(np.abs(run.bounds - run.nominal_bounds) > 1e-12, axis=1)
    assert s["settling_time"] == ts
    assert s["steady_rms"] == pytest.approx(math.sqrt(float(np.mean(z1[tail] ** 2))), rel=1e-12)
    assert s["ripple"] == pytest.approx(float(u[tail].max() - u[tail].min()), rel=1e-12)
    assert s["max_abs_xi_nominal"] == float(np.max(np.abs(run.xi_nominal)))
    assert s["saturated_fraction"] == pytest.approx(float(np.mean(sat)))
    assert s["expanded_unsaturated_fraction"] == pytest.approx(float(np.mean(expanded & ~sat)))
    assert s["neg_f_over_g_error"] is None and s["derivatives_error"] is None
    # the text says the same in a few lines
    assert str(s) == s.text and len(s.text.splitlines()) <= 3
    assert f"at {ts:.3g} s" in s.text and f"steady RMS {s['steady_rms']:.3g} rad" in s.text
    assert f"{s['ripple']:.3g} V (peak-to-peak)" in s.text
    # backward compatible: an explicit eps, the flat dict's keys
    old = run.summary(eps=0.1)
    assert old["eps"] == 0.1 and old["settling_time"] == run.settling_time(0.1)
    assert {"first_entry", "max_abs_xi", "u_min", "u_max", "clamp_count"} <= set(old)


def test_summary_without_a_known_accuracy_says_so():
    # LoMC at order 2 without a skew presets no accuracy of z1
    ctrl = famcc.Controller(2, 1e-3, famcc.Linear(2.0), constraint="longitudinal", eps=0.1, k_u=2.0)
    res = famcc.simulate(motor(), ctrl, 1.0, reference=famcc.Constant(0.5), u_limits=(-5, 5))
    assert res.accuracy is None
    s = res.summary()
    assert s["eps"] is None and s["settling_time"] is None and s["ripple"] is None
    assert "no accuracy eps known" in s.text
    assert res.summary(eps=0.05)["eps"] == 0.05


def test_accuracy_comes_from_the_configuration():
    def acc(*args, **kw):
        ctrl = famcc.Controller(*args, **kw)
        return famcc.simulate(
            famcc.plants.second_order() if ctrl.order == 2 else famcc.plants.third_order(),
            ctrl,
            0.01,
            reference=famcc.Sine(),
        ).accuracy

    law = famcc.FiniteTime(k=1.0, p=0.5)
    assert acc(2, 1e-3, law, constraint="lateral", eps=0.1, k_u=5.0) == 0.1
    smooth = famcc.Smooth(eps_s=0.2, eps_z=0.07)
    assert acc(2, 1e-3, law, skew=smooth, eps=0.15, k_u=2.0) == 0.07
    assert famcc.scenarios.paper("rfc").run(t_end=0.01).accuracy == 0.1  # stage 1's eps_z
    assert acc(2, 1e-3, famcc.Linear(1.0), eps=0.15, k_u=2.0) is None


def test_rich_views_for_jupyter(run):
    png = run._repr_png_()
    assert png[:8] == PNG_MAGIC and run._repr_png_() is png  # drawn once
    page = run._repr_html_()
    assert page.startswith("<div>") and "data:image/png;base64," in page
    assert "<table>" in page and "settling_time" in page and "voltage [V]" in page


def test_to_dataframe(run):
    import pandas as pd  # in the test extra

    df = run.to_dataframe()
    assert isinstance(df, pd.DataFrame) and df.index.name == "t" and len(df) == len(run.t)
    for col in ("y", "y_d", "x1", "x2", "z1", "z2", "z_hat1", "v", "u", "saturated", "xi"):
        assert col in df.columns
    np.testing.assert_array_equal(df["u"].to_numpy(), run.u)
    np.testing.assert_array_equal(df["bound_x"].to_numpy(), run.bounds[:, 0])
    assert df.attrs["output"] == ("angle", "rad") and df.attrs["input"] == ("voltage", "V")


def test_to_dataframe_without_pandas_names_the_fix(run, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now raises ImportError
    with pytest.raises(ImportError, match="pip install pandas"):
        run.to_dataframe()


# -- explicit rather than silent --------------------------------------------------------------


def test_missing_neg_f_over_g_is_explained():
    ctrl = famcc.Controller(
        2, 1e-3, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral", eps=0.05, k_u=5.0
    )
    res = famcc.simulate(pendulum(), ctrl, 2.0, reference=famcc.Constant(0.0), u_limits=(-4, 4))
    assert res.neg_f_over_g is None
    # the plant's own error: its callables compare a jet
    assert "accept jets" in res.neg_f_over_g_error and "'>'" in res.neg_f_over_g_error
    assert res.derivatives_error is None  # z2 needs no jets at order 2
    s = res.summary()
    assert s["neg_f_over_g_error"] == res.neg_f_over_g_error
    assert "-F/G unknown: " in s.text and "-F/G unknown" in repr(res)
    fig = res.plot(["input"])
    notes = " ".join(text.get_text() for text in fig.axes[0].texts)
    assert "$-F/G$ unknown" in notes and "jets" in notes
    assert [line.get_label() for line in fig.axes[0].get_lines()].count("$-F/G$") == 0


def test_other_reasons_for_missing_neg_f_over_g_and_derivatives():
    ctrl = motor_controller()
    short_ref = (lambda t: 1.0, lambda t: 0.0)  # y_d and y_d' only: -F/G needs y_d''
    res = famcc.simulate(motor(), ctrl, 0.2, reference=short_ref)
    assert res.neg_f_over_g is None and "y_d^(2)" in res.neg_f_over_g_error
    res = famcc.simulate(motor(), motor_controller(), 0.2, reference=famcc.Sine(), record=False)
    assert res.neg_f_over_g_error == "not computed: simulate(record=False)"

    class Bare(famcc.plants.Plant):  # only the vector field
        def rhs(self, t, x, u):
            return np.array([x[1], u - x[1]])

    res = famcc.simulate(Bare(2, [0.3, 0.0]), motor_controller(), 0.2, reference=famcc.Sine())
    assert "cannot report its output derivatives" in res.derivatives_error
    assert "cannot report its total gain and drift" in res.neg_f_over_g_error
    assert np.all(np.isnan(res.z[:, 1]))
    assert "; z2 unknown: " in res.summary().text


def test_no_reference_warns_and_means_the_papers_sine():
    ctrl = motor_controller()
    with pytest.warns(famcc.DefaultReferenceWarning, match=r"y_d = sin t.*famcc.Sine\(\)"):
        default = famcc.simulate(motor(), ctrl, 0.5)
    assert issubclass(famcc.DefaultReferenceWarning, FutureWarning)
    explicit = famcc.simulate(motor(), motor_controller(), 0.5, reference=famcc.Sine())
    np.testing.assert_array_equal(default.x, explicit.x)
    np.testing.assert_allclose(default.y_d, np.sin(default.t), atol=1e-15)
    assert "by default" in default.reference_repr


def test_the_paper_scenarios_pass_their_reference_and_warn_nothing():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = famcc.scenarios.paper("rfc").run(t_end=0.2)
    assert res.reference_repr.startswith("Sine(")


def test_constant_reference():
    ref = famcc.Constant(2.5)
    assert [ref(1.0, k) for k in range(3)] == [2.5, 0.0, 0.0]
    res = famcc.simulate(motor(), motor_controller(), 0.1, reference=ref)
    assert np.all(res.y_d == 2.5) and res.neg_f_over_g is not None
    with pytest.raises(ValueError, match="value"):
        famcc.Constant(math.nan)


def test_names_and_units_can_be_given_to_simulate():
    res = famcc.simulate(
        famcc.plants.second_order(),
        motor_controller(),
        0.05,
        reference=famcc.Sine(),
        output=("height", "m"),
        input="pump",
    )
    assert res.output == famcc.Signal("height", "m") and res.input == famcc.Signal("pump")
    assert res.plot(["input"]).axes[0].get_ylabel() == "pump $u$"  # no invented unit
    assert famcc.Signal("speed", "m/s").derivative_unit(2) == "(m/s)/s²"
    with pytest.raises(ValueError, match="name, unit"):
        famcc.simulate(
            motor(), motor_controller(), 0.05, reference=famcc.Sine(), output=("a", "b", "c")
        )


# -- famcc.report for a user's runs ---------------------------------------------------------


def _two_runs():
    return [("k_u = 2", motor_run(2.0)), ("k_u = 0.5", motor_run(0.5, limits=(-1.0, 1.0)))]


def test_report_of_two_user_runs(tmp_path):
    runs = _two_runs()
    md = famcc.report(runs, out=tmp_path)
    text = md.read_text()
    assert md == tmp_path / "report.md"
    for head in ("# famcc report", "## Results", "## Claims", "## Notes", "## Figures"):
        assert head in text
    results = text.split("## Results")[1].split("## Claims")[0]
    assert results.count("| k_u = 2 |") == 1 and results.count("| k_u = 0.5 |") == 1
    # no requirements: no claims, and the headline says so instead of counting nothing
    assert "No claims tested: no requirements were given" in text
    assert "No claims: no requirements were given." in text
    for stem in ("k-u-2", "k-u-0-5"):
        assert f"]({stem}.png)" in text
        assert (tmp_path / f"{stem}.png").read_bytes()[:8] == PNG_MAGIC
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [r["label"] for r in summary["runs"]] == ["k_u = 2", "k_u = 0.5"]
    assert summary["guarantees"]["total"] == 0 and summary["all_guarantees_hold"] is False
    first = summary["runs"][0]
    assert first["settling_time"] == runs[0][1].settling_time(0.02)
    assert first["output"] == ["angle", "rad"] and first["input"] == ["voltage", "V"]
    # the weak, saturating run is explained in plain words
    assert "**k_u = 0.5.** u stayed in" in text


def test_report_judges_requirements_honestly(tmp_path):
    runs = _two_runs()
    ts = [res.settling_time(0.05) for _, res in runs]
    assert ts[0] < 1.5 < ts[1]  # the fast run settles by 1.5 s, the slow one later
    famcc.report(runs, out=tmp_path, eps=0.05, settle_time=1.5, figures=False)
    summary = json.loads((tmp_path / "summary.json").read_text())
    status = [r["verdicts"][0]["status"] for r in summary["runs"]]
    assert status == ["held", "failed"]
    text = (tmp_path / "report.md").read_text()
    assert "**2 of 2 guarantees tested: 1 hold, 1 fail; 0 untested**" in text
    # a requirement beyond the horizon cannot be tested, and is never counted as held
    famcc.report(runs, out=tmp_path, eps=0.05, settle_time=10.0, figures=False)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [r["verdicts"][0]["status"] for r in summary["runs"]] == ["untested"] * 2
    assert summary["all_guarantees_hold"] is False and summary["guarantees"]["held"] == 0
    with pytest.raises(ValueError, match="give eps too"):
        famcc.report(runs, out=tmp_path, settle_time=1.0)


def test_report_explains_a_missing_neg_f_over_g(tmp_path):
    ctrl = famcc.Controller(
        2, 1e-3, famcc.FiniteTime(k=2.0, p=0.5), constraint="lateral", eps=0.05, k_u=5.0
    )
    res = famcc.simulate(pendulum(), ctrl, 1.0, reference=famcc.Constant(0.0))
    famcc.report(res, out=tmp_path, figures=False)
    text = (tmp_path / "report.md").read_text()
    assert "**run 1: -F/G unknown.**" in text and "accept jets" in text


def test_report_rejects_what_is_not_a_run(tmp_path):
    with pytest.raises(ValueError, match="SimResult"):
        famcc.report([1, 2], out=tmp_path)
    with pytest.raises(ValueError, match="empty"):
        famcc.report([], out=tmp_path)
    res = motor_run(t_end=0.2)
    with pytest.raises(ValueError, match="unique"):
        famcc.report([("a", res), ("a", res)], out=tmp_path)
    assert isinstance(res, SimResult)


def test_settled_by_can_fail_hold_and_stay_untested():
    t = np.arange(0, 2.001, 0.01)
    z1 = np.where(t < 1.0, 1.0, 0.0)
    r = SimResult(t=t, y=z1, y_d=0 * t, x=z1[:, None], z=z1[:, None], v=0 * t, u=0 * t, dt=0.01)
    assert verdicts.settled_by(r, 0.1, 1.0).status == "held"
    failed = verdicts.settled_by(r, 0.1, 0.5)
    assert failed.status == "failed" and "settled only at 1.000 s" in failed.detail
    assert verdicts.settled_by(r, 0.1, 3.0).status == "untested"
    never = SimResult(t=t, y=t, y_d=0 * t, x=t[:, None], z=t[:, None], v=0 * t, u=0 * t, dt=0.01)
    assert verdicts.settled_by(never, 0.1, 2.0).status == "failed"
    assert verdicts.requirements(never, eps=0.1)[0].status == "failed"  # settles, by the end
