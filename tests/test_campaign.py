"""famcc.campaigns: lockstep Monte Carlo campaigns that famcc.simulate reproduces case by case."""

from __future__ import annotations

import concurrent.futures as cf
import importlib
import math
import time

import famcc
import numpy as np
import pytest
from famcc import campaigns
from famcc.campaigns import Choice, LogUniform, Normal, Uniform, campaign
from famcc.families import Family, family

HAS_BANK_DIAG = hasattr(famcc.ControllerBank, "xi_nominal")


def _ex1(**kw):
    """A small campaign of the paper's example 1 on dispersed second-order plants."""
    args = {
        "cases": 24,
        "t_end": 2.0,
        "u_limits": (-2.5, 3.0),
        "reference": famcc.Sine(),
        "eps": 0.1,
        "dispersion": {
            "gain": Uniform(0.6, 1.4),
            "amp": Uniform(1.0, 4.0),
            "x1(0)": Uniform(-2.0, 1.0),
            "reference.omega": Uniform(0.5, 2.0),
        },
        "executor": "serial",
        "chunk_size": 10,
        "progress": False,
        "seed": 11,
    }
    args.update(kw)
    return campaign("second-order", famcc.scenarios.paper("finite-time").controller(), **args)


def _same_tables(a, b):
    assert list(a.table) == list(b.table)
    for key in a.table:
        x, y = a.table[key], b.table[key]
        if x.dtype.kind == "f":
            assert np.array_equal(x, y, equal_nan=True), key
        else:
            assert np.array_equal(x, y), key


# -- the beta quantile and the Clopper-Pearson interval ---------------------------


def test_beta_quantile_matches_known_values_and_scipy():
    stats = pytest.importorskip("scipy.stats")  # scipy comes with python-control (test extra)
    assert campaigns.beta_ppf(0.5, 2.0, 2.0) == pytest.approx(0.5, abs=1e-14)
    # Beta(1, b): I_x = 1 - (1 - x)^b, so the quantile is 1 - (1 - q)^(1/b)
    assert campaigns.beta_ppf(0.975, 1.0, 10.0) == pytest.approx(1 - 0.025**0.1, abs=1e-13)
    for a, b in ((0.5, 0.5), (1.0, 3.0), (3.0, 7.0), (50.0, 2.0), (9812.0, 189.0), (1.0, 9999.0)):
        for q in (1e-6, 0.025, 0.3, 0.5, 0.975, 1 - 1e-6):
            want = float(stats.beta.ppf(q, a, b))
            assert campaigns.beta_ppf(q, a, b) == pytest.approx(want, rel=1e-9, abs=1e-13)
            assert campaigns.beta_cdf(want, a, b) == pytest.approx(q, rel=1e-9, abs=1e-13)


def test_clopper_pearson_known_intervals():
    lo, hi = campaigns.clopper_pearson(5, 10)
    assert (round(lo, 4), round(hi, 4)) == (0.1871, 0.8129)  # the textbook example
    n = 300
    assert campaigns.clopper_pearson(0, n) == (0.0, pytest.approx(1 - 0.025 ** (1 / n)))
    assert campaigns.clopper_pearson(n, n) == (pytest.approx(0.025 ** (1 / n)), 1.0)
    lo, hi = campaigns.clopper_pearson(20, 300, confidence=0.99)
    assert lo < 20 / 300 < hi
    with pytest.raises(ValueError, match="0 <= k <= n"):
        campaigns.clopper_pearson(11, 10)


# -- the families compute their scalar plants' arithmetic ---------------------------


@pytest.mark.parametrize("name", famcc.families.names())
def test_family_rhs_equals_the_scalar_plant_bit_for_bit(name):
    fam = family(name)
    rng = np.random.default_rng(3)
    n, m = fam.order, 64
    x = rng.uniform(-2.0, 2.0, size=(n, m))
    u = rng.uniform(-5.0, 5.0, size=m)
    p = {k: v * rng.uniform(0.7, 1.3, size=m) for k, v in fam.params.items()}
    for t in (0.0, 0.37, 2.004):
        dx = fam.rhs(t, x, u, p)
        for i in range(0, m, 7):
            plant = fam.plant(x0=x[:, i], **{k: float(v[i]) for k, v in p.items()})
            scalar = plant.rhs_fast(t, x[:, i].tolist(), float(u[i]))
            assert np.array_equal(dx[:, i], np.array(scalar)), (t, i)


def test_nominal_family_members_are_the_papers_plants():
    for variant in famcc.plants.VARIANTS:
        ref = famcc.plants.second_order(variant)
        mine = family("second-order", variant).plant()
        x = np.array([0.3, -0.8])
        assert mine.rhs_fast(1.3, x.tolist(), 0.7) == ref.rhs_fast(1.3, x.tolist(), 0.7)
        assert np.array_equal(mine.gain_and_drift(1.3, x), ref.gain_and_drift(1.3, x))
        assert np.array_equal(mine.x0, ref.x0)
        ref3 = famcc.plants.third_order(variant)
        mine3 = family("third-order", variant).plant()
        x3 = np.array([0.3, -0.8, 1.1])
        assert np.array_equal(mine3.gain_and_drift(0.4, x3), ref3.gain_and_drift(0.4, x3))
        assert np.array_equal(mine3.x0, ref3.x0)


def test_own_family_and_its_default_member():
    def rhs(t, x, u, p):
        return (x[1], p["b"] * u - p["c"] * x[1] + 0.0)

    fam = Family("oscillator", 2, rhs, {"b": 2.0, "c": 0.5}, [1.0, 0.0])
    member = fam.plant(x0=[0.5, 0.0], c=1.0)
    assert np.array_equal(member.rhs(0.0, np.array([0.5, 1.0]), 2.0), [1.0, 3.0])
    with pytest.raises(ValueError, match="no parameter 'd'"):
        fam.plant(d=1.0)
    with pytest.raises(ValueError, match="x0 must be 2"):
        Family("bad", 2, rhs, {}, [1.0])


# -- campaign == simulate, case by case ---------------------------------------------


def _check_reproduces(res, cases):
    for i in cases:
        row = res.row(i)
        assert not row["diverged"]
        sim = res.case(i).simulate()
        st = sim.settling_time(res.spec.eps)
        fe = sim.first_entry(res.spec.eps)
        assert (math.nan if st is None else st) == pytest.approx(
            row["settling_time"], nan_ok=True, abs=0.0
        ), i
        assert (math.nan if fe is None else fe) == pytest.approx(
            row["first_entry"], nan_ok=True, abs=0.0
        ), i
        assert sim.saturated_fraction == row["saturated_fraction"], i
        if HAS_BANK_DIAG:
            assert sim.max_abs_xi_nominal == row["max_abs_xi_nominal"], i
            assert sim.expanded_unsaturated_fraction == row["expanded_unsaturated_fraction"], i
        else:
            assert math.isnan(row["max_abs_xi_nominal"])


def test_simulate_reproduces_each_case_of_a_saturated_campaign_with_noise():
    res = _ex1(
        noise=2e-3,
        dispersion={
            "gain": Uniform(0.6, 1.4),
            "x1(0)": Uniform(-2.0, 1.0),
            "x2(0)": Normal(0.5, 0.3),
            "reference.amplitude": Uniform(0.5, 1.5),
            "reference.phase": Uniform(-1.0, 1.0),
            "controller.k_u": Choice([4.0, 6.0]),
            "noise.sigma": LogUniform(1e-4, 1e-2),
        },
    )
    assert res.rate("bounded").held == res.n
    assert 0 < res.table["saturated_fraction"].mean() < 1  # the limits really bite
    assert set(np.unique(res.table["controller.k_u"])) == {4.0, 6.0}
    _check_reproduces(res, range(res.n))


def test_simulate_reproduces_third_order_and_physical_cases():
    rfc = famcc.scenarios.paper("rfc-saturated")
    res = campaign(
        "third-order",
        rfc.controller(),
        cases=6,
        t_end=1.5,
        u_limits=rfc.u_limits,
        reference=famcc.Sine(),
        eps=0.1,
        substeps=2,
        executor="serial",
        dispersion={"gain": Uniform(0.8, 1.2), "x3(0)": Uniform(2.0, 6.0)},
        progress=False,
        seed=5,
    )
    _check_reproduces(res, range(res.n))
    motor = famcc.Controller(
        2, 1e-3, famcc.Linear(4.0), constraint="lateral", eps=0.02, k_u=20.0, settle_time=0.5
    )
    res = campaign(
        "dc-motor",
        motor,
        cases=6,
        t_end=3.0,
        u_limits=(-12.0, 12.0),
        reference=famcc.Constant(0.5),
        executor="serial",
        progress=False,
        dispersion={
            "J": Uniform(0.005, 0.02),
            "load": Uniform(0.0, 2.0),
            "t_load": Uniform(1.0, 2.0),
            "reference.value": Uniform(0.2, 1),
        },
    )
    assert isinstance(res.case(0).plant, famcc.plants.PhysicalPlant)
    _check_reproduces(res, range(res.n))


# -- determinism, executors, resuming ---------------------------------------------------


def test_results_do_not_depend_on_chunks_or_executor():
    a = _ex1()
    b = _ex1(chunk_size=7)
    c = _ex1(chunk_size=24)
    with cf.ThreadPoolExecutor(2) as pool:
        d = _ex1(executor=pool, chunk_size=5)
    e = _ex1(executor=None, jobs=2, chunk_size=12)  # local processes
    for other in (b, c, d, e):
        _same_tables(a, other)
    # more cases extend the campaign: the first ones stay the same
    f = _ex1(cases=30)
    for key in ("gain", "settling_time", "saturated_fraction"):
        assert np.array_equal(f.table[key][:24], a.table[key], equal_nan=True)
    assert not np.array_equal(_ex1(seed=12).table["gain"], a.table["gain"])


@pytest.mark.cluster  # dask and distributed: the cluster extra (tests/conftest.py)
def test_dask_cluster_gives_the_same_2000_cases_as_local_processes():
    distributed = importlib.import_module("distributed")
    t0 = time.perf_counter()
    kw = {"cases": 2000, "t_end": 0.3, "chunk_size": 250, "seed": 2000}
    local = _ex1(executor=None, jobs=2, **kw)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        on_dask = _ex1(executor=client, **kw)
        assert len(client.scheduler_info()["workers"]) == 2
        # a scheduler address (famcc campaign --scheduler): famcc opens and closes a client
        by_address = _ex1(executor=cluster.scheduler_address, cases=40, t_end=0.3, seed=2000)
        assert len(client.scheduler_info()["workers"]) == 2  # the cluster is still there
    _same_tables(local, on_dask)
    for key in ("settling_time", "saturated_fraction", "max_abs_xi_nominal"):
        assert np.array_equal(by_address.table[key], local.table[key][:40], equal_nan=True)
    assert local.n == 2000 and local.rate("bounded").tested == 2000
    assert time.perf_counter() - t0 < 120  # the budget is ~60 s; a loaded machine is slower


class _Counting(cf.ThreadPoolExecutor):
    def __init__(self):
        super().__init__(1)
        self.submitted = 0

    def submit(self, *args, **kwargs):
        self.submitted += 1
        return super().submit(*args, **kwargs)


def test_finished_chunks_are_skipped_on_a_rerun(tmp_path):
    first = _Counting()
    a = _ex1(executor=first, out=tmp_path)
    chunks = sorted((tmp_path / "chunks").glob("chunk-*.npz"))
    assert first.submitted == 3 and len(chunks) == 3
    again = _Counting()
    b = _ex1(executor=again, out=tmp_path)
    assert again.submitted == 0
    _same_tables(a, b)
    chunks[1].unlink()  # an interrupted run: one chunk missing
    partly = _Counting()
    c = _ex1(executor=partly, out=tmp_path)
    assert partly.submitted == 1
    _same_tables(a, c)
    with pytest.raises(ValueError, match="holds another campaign"):
        _ex1(out=tmp_path, seed=99)


# -- criteria that can fail, divergence, honesty -----------------------------------------


def _escaping(t, x, u, p):
    """y'' = 2 u + c y^3: for c = 50 the state escapes to infinity within 0.3 s."""
    return (x[1], 2.0 * u + p["c"] * x[0] * x[0] * x[0])


def test_diverged_cases_are_flagged_without_killing_their_chunk():
    fam = Family("escaping", 2, _escaping, {"c": 0.0}, [1.0, 0.0])
    ctrl = famcc.scenarios.paper("finite-time").controller()

    def run(c):
        return campaign(
            fam,
            ctrl,
            cases=20,
            t_end=2.0,
            reference=famcc.Constant(0.0),
            eps=0.1,
            dispersion={"c": c},
            executor="serial",
            chunk_size=20,
            progress=False,
            seed=4,
        )

    res = run(Choice([0.0, 50.0]))
    escapes = res.table["c"] > 0
    assert escapes.any() and (~escapes).any()
    assert np.array_equal(res.table["diverged"], escapes)
    assert np.all(res.table["bounded"][escapes] == 0)
    assert np.all(res.table["success"][escapes] == 0)
    assert np.all(np.isnan(res.table["settling_time"][escapes]))
    assert np.all(
        (res.table["diverged_at"][escapes] > 0) & (res.table["diverged_at"][escapes] < 0.5)
    )
    assert res.worst(1)[0]["diverged"]
    # the others are exactly what they are in a campaign without the escaping ones
    calm = run(Choice([0.0]))
    assert calm.rate("bounded").held == calm.n
    for key in ("settling_time", "saturated_fraction", "max_abs_xi_nominal"):
        assert np.array_equal(
            res.table[key][~escapes], calm.table[key][~escapes], equal_nan=True
        ), key


def test_every_criterion_can_fail_and_be_untested():
    tight = _ex1(settle_by=0.2, u_limits=(-1.0, 1.0))
    assert tight.rate("settled").failed > 0 and tight.rate("unsaturated").failed > 0
    later = _ex1(settle_by=5.0)  # beyond the 2 s horizon: nobody can tell
    assert later.rate("settled").untested == later.n and later.rate("settled").tested == 0
    assert later.rate("success").untested == later.n
    assert math.isnan(later.rate("settled").rate)
    unlimited = _ex1(u_limits=None)
    assert unlimited.rate("unsaturated").untested == unlimited.n
    if HAS_BANK_DIAG:  # a weak k_u expands the bounds although the actuator has headroom
        weak = _ex1(u_limits=None, dispersion={"controller.k_u": Choice([0.3])})
        assert weak.rate("nominal").failed > 0
    good = _ex1(u_limits=(-100.0, 100.0), settle_by="bound", t_end=4.0)
    assert good.rate("settled").held > 0


def test_bound_deadline_follows_the_corollary():
    res = _ex1(settle_by="bound", u_limits=(-100.0, 100.0), t_end=4.0)
    z1_0 = res.table["x1(0)"] - 0.0  # y_d(0) = sin(0) = 0
    want = np.maximum(res.table["last_saturation_end"], 1.0) + 2.0 * np.sqrt(np.abs(z1_0))
    assert np.allclose(res.table["deadline"], want, rtol=1e-12)
    with pytest.raises(ValueError, match="corollary bound"):
        campaign(
            "second-order",
            famcc.Controller(2, 1e-3, famcc.Linear(1.0), eps=0.1, k_u=5.0, constraint="lateral"),
            cases=2,
            t_end=1.0,
            reference=famcc.Sine(),
            settle_by="bound",
            executor="serial",
            progress=False,
        )


# -- results, exports, figures, report -------------------------------------------------


def test_rates_worst_cases_and_exports(tmp_path, monkeypatch):
    res = _ex1(settle_by=1.5)
    r = res.rate()
    assert r.held + r.failed + r.untested == res.n
    assert r.lo <= r.rate <= r.hi
    assert "CI" in r.text() and res.summary().startswith("campaign: 24 cases")
    worst = res.worst(5)
    assert len(worst) == 5 and set(res.spec.values) <= set(worst[0])
    ranks = [(0 if w["diverged"] else 1 if w["success"] == 0 else 2) for w in worst]
    assert ranks == sorted(ranks)
    df = res.to_dataframe()
    assert len(df) == res.n and "settling_time" in df and df.index.name == "case"
    back = importlib.import_module("pandas").read_parquet(res.to_parquet(tmp_path / "c.parquet"))
    assert np.array_equal(back["saturated_fraction"], res.table["saturated_fraction"])
    csv = res.to_csv(tmp_path / "c.csv").read_text().splitlines()
    assert len(csv) == res.n + 1 and csv[0].startswith("case,gain")

    real = importlib.import_module

    def missing(name, *a, **k):
        if name in ("pandas", "pyarrow"):
            raise ImportError(f"No module named {name!r}")
        return real(name, *a, **k)

    monkeypatch.setattr(importlib, "import_module", missing)
    with pytest.raises(ImportError, match="needs pandas.*pip install pandas"):
        res.to_dataframe()
    with pytest.raises(ImportError, match="needs pyarrow.*pip install pyarrow"):
        res.to_parquet(tmp_path / "x.parquet")


def test_report_names_rate_interval_and_worst_cases(tmp_path):
    res = _ex1(settle_by=1.5)
    md = res.write(tmp_path).read_text()
    r = res.rate()
    assert f"{r.held:,} of {r.tested:,}" in md and "95 % CI" in md and "failure rate" in md
    assert "## The 10 worst cases" in md and "| case | gain |" in md
    for name in ("distributions.png", "success.png", "cases.csv", "cases.parquet"):
        assert (tmp_path / name).stat().st_size > 0


def test_cli_campaign_runs_a_spec(tmp_path, capsys):
    spec = tmp_path / "small.toml"
    spec.write_text(
        'name = "tiny"\ncases = 12\nt_end = 1.0\nchunk_size = 6\nu_limits = [-2.5, 3.0]\n'
        '[plant]\nfamily = "second-order"\n[controller]\nscenario = "finite-time"\n'
        "[criteria]\neps = 0.1\n[dispersion.plant]\ngain = {uniform = [0.8, 1.2]}\n"
        "[dispersion.x0]\nx1 = {uniform = [-1.5, 0.5]}\n"
        "[dispersion.controller]\nk_u = {choice = [5.0, 6.0]}\n"
    )
    from famcc import cli

    assert cli.main(["campaign", str(spec), "--out", str(tmp_path / "out"), "--jobs", "1"]) == 0
    md = (tmp_path / "out" / "report.md").read_text()
    assert "tiny: 12 cases" in md and "worst cases" in md
    assert "report:" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text(spec.read_text().replace("[criteria]", "[criteria]\nfast = true"))
    assert cli.main(["campaign", str(bad), "--out", str(tmp_path / "x"), "--quiet"]) == 2
    assert "unknown keys ['fast'] in [criteria]" in capsys.readouterr().err


def test_shipped_specs_load():
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "examples" / "campaigns"
    specs = sorted(root.glob("*.toml"))
    assert [p.stem for p in specs] == ["finite-time", "rfc-saturated", "variable-exponent"]
    for p in specs:
        kw = campaigns.load_spec(p)
        assert kw["cases"] == 10_000 and kw["controller"].order in (2, 3)


def test_bad_arguments_name_themselves():
    ctrl = famcc.scenarios.paper("finite-time").controller()
    base = {
        "cases": 4,
        "t_end": 1.0,
        "reference": famcc.Sine(),
        "executor": "serial",
        "progress": False,
    }
    with pytest.raises(ValueError, match="unknown dispersion key 'J'"):
        campaign("second-order", ctrl, dispersion={"J": 1.0}, **base)
    with pytest.raises(ValueError, match="order"):
        campaign("third-order", ctrl, **base)
    with pytest.raises(ValueError, match="reference must be famcc.Sine"):
        campaign("second-order", ctrl, **{**base, "reference": None})
    with pytest.raises(ValueError, match="uniform needs lo <= hi"):
        campaign("second-order", ctrl, dispersion={"gain": {"uniform": [2, 1]}}, **base)
    with pytest.raises(ValueError, match="require"):
        campaign("second-order", ctrl, require=["fast"], **base)
    with pytest.raises(ValueError, match="executor must be"):
        campaign("second-order", ctrl, **{**base, "executor": 3})


def test_a_design_object_is_accepted():
    class Design:  # what famcc.design / famcc.tune return: controller() builds the controller
        def controller(self):
            return famcc.scenarios.paper("finite-time").controller()

    res = campaign(
        "second-order",
        Design(),
        cases=3,
        t_end=0.5,
        reference=famcc.Sine(),
        executor="serial",
        progress=False,
    )
    assert res.n == 3 and res.spec.eps == 0.1
