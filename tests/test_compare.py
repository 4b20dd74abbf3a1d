"""famcc compare: the quick run writes its report, and the report's claims follow from its numbers."""

from __future__ import annotations

import copy
import json
import re

import numpy as np
import pytest
from famcc import cli
from famcc import compare as cmp

PEERS = ("lmcc", "pid", "adrc")


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("compare")
    assert cli.main(["compare", "--quick", "--out", str(out), "--quiet", "--jobs", "2"]) == 0
    return out, json.loads((out / "results.json").read_text())


def test_the_quick_run_writes_report_numbers_and_figures(quick):
    out, data = quick
    md = (out / "report.md").read_text()
    assert md.startswith("# famcc compare")
    assert re.search(r"\*\*\d+ s\*\* wall time", md)  # the run time is stated
    for name in data["meta"]["cases"]:
        assert f"## {name}" in md
        for fig in (f"{name}-radar.png", f"{name}-series.png"):
            assert (out / "figures" / fig).stat().st_size > 1000 and f"figures/{fig}" in md
    assert "## Where famcc loses" in md
    assert set(data["meta"]["controllers"]) == {"famcc", *PEERS}
    # every controller ran every condition on every plant, with the same budget
    for name, runs in data["runs"].items():
        for kind in data["meta"]["controllers"]:
            assert set(runs[kind]) == set(data["meta"]["conditions"])
            assert len(data["tuned"][name][kind]["history"]) == data["meta"]["budget"]


def _my_losses(data):
    """An independent reading of the rule: who beats famcc by more than 1.1x, or where."""
    found = set()
    for name, runs in data["runs"].items():
        for cond in data["meta"]["conditions"]:
            f = runs["famcc"][cond]
            for flag in ("diverged", "never_settled"):
                if f.get(flag) and any(not runs[p][cond].get(flag) for p in PEERS):
                    found.add((name, cond, flag))
            if f.get("diverged"):
                continue
            for metric in ("iae", "final_rms", "tv_u"):
                mine = f.get(metric)
                theirs = [
                    runs[p][cond].get(metric)
                    for p in PEERS
                    if not runs[p][cond].get("diverged") and runs[p][cond].get(metric) is not None
                ]
                if mine is not None and theirs and min(theirs) * 1.1 < mine:
                    found.add((name, cond, metric))
    return found


def test_where_famcc_loses_follows_from_the_numbers(quick):
    out, data = quick
    md = (out / "report.md").read_text()
    listed = {(x["case"], x["condition"], x["metric"]) for x in data["losses"]}
    assert listed == _my_losses(data)
    section = md.split("## Where famcc loses", 1)[1]
    for x in data["losses"]:
        assert f"- {cmp.loss_text(x)}" in section
        if x["metric"] in ("iae", "final_rms", "tv_u"):
            winner = data["runs"][x["case"]][x["winners"][0]][x["condition"]][x["metric"]]
            assert x["peer"] == winner and x["famcc"] == pytest.approx(
                data["runs"][x["case"]]["famcc"][x["condition"]][x["metric"]]
            )
            assert x["peer"] * 1.1 < x["famcc"]


def test_a_loss_line_names_what_each_side_did() -> None:
    base = {"case": "pendulum", "condition": "200 Hz", "winners": ["pid", "adrc"]}
    settled = cmp.loss_text({**base, "metric": "never_settled"})
    assert settled == "pendulum, 200 Hz: famcc never settled to the band; pid, adrc settled."
    diverged = cmp.loss_text({**base, "metric": "diverged"})
    assert diverged.endswith("famcc diverged; pid, adrc did not diverge.")
    line = {**base, "metric": "iae", "famcc": 0.3, "peer": 0.1, "ratio": 3.04}
    assert cmp.loss_text(line).endswith("IAE pid 0.1 vs famcc 0.3 (3.0x)")
    # A peer at rounding-error level (1e-16 against 5e-3) gives an order, not 16 digits.
    tiny = {**line, "metric": "final_rms", "famcc": 5e-3, "peer": 3e-16, "ratio": 1.6e13}
    assert cmp.loss_text(tiny).endswith("(>1000x)")


def test_the_tables_show_the_numbers_and_bold_the_best_iae(quick):
    out, data = quick
    md = (out / "report.md").read_text()
    label = {"famcc": "famcc", "lmcc": "LMCC", "pid": "PID", "adrc": "ADRC"}
    for name, runs in data["runs"].items():
        block = md.split(f"## {name}", 1)[1].split("\n## ", 1)[0]
        for cond in data["meta"]["conditions"]:
            live = {
                k: m["iae"] for k, m in ((k, runs[k][cond]) for k in runs) if not m.get("diverged")
            }
            for kind, m in ((k, runs[k][cond]) for k in runs):
                row = re.search(
                    rf"^\| {re.escape(cond)} \| {label[kind]} \| ([^|]+) \|", block, re.MULTILINE
                )
                assert row, (name, cond, kind)
                cell = row.group(1).strip()
                assert cell.strip("*") == f"{m['iae']:.3g}"
                assert cell.startswith("**") == (kind in live and live[kind] == min(live.values()))


def test_radar_scores_rank_the_controllers(quick):
    _, data = quick
    for name in data["meta"]["cases"]:
        scores = cmp.radar_scores(data, name)
        axes = {a for s in scores.values() for a in s}
        assert axes == {a for a, _, _ in cmp.RADAR}
        for axis in axes:
            vals = [s[axis] for s in scores.values()]
            assert all(0.0 <= v <= 1.0 for v in vals) and max(vals) == 1.0


def _fake():
    """Two plants' worth of numbers where famcc wins everything."""
    m = {
        "iae": 1.0,
        "final_rms": 0.01,
        "tv_u": 10.0,
        "settling_time": 1.0,
        "rms_u": 1.0,
        "diverged": False,
        "never_settled": False,
    }
    runs = {k: {c: dict(m) for c in cmp.CONDITIONS} for k in cmp.controllers()}
    return {
        "meta": {"conditions": list(cmp.CONDITIONS)},
        "cases": {"p": {"t_end": 10.0}},
        "runs": {"p": runs},
    }


def test_losses_and_scores_can_fail():
    data = _fake()
    assert cmp.losses(data) == []
    # a peer 5 % better is no loss, 20 % better is one; each metric on its own
    for metric in ("iae", "final_rms", "tv_u"):
        d = copy.deepcopy(data)
        d["runs"]["p"]["pid"]["nominal"][metric] *= 0.95
        assert cmp.losses(d) == []
        d["runs"]["p"]["pid"]["nominal"][metric] = data["runs"]["p"]["pid"]["nominal"][metric] / 1.2
        (loss,) = cmp.losses(d)
        assert (loss["metric"], loss["winners"], loss["condition"]) == (metric, ["pid"], "nominal")
        assert loss["ratio"] == pytest.approx(1.2)
    # famcc's flags: a loss where a peer has none
    for flag in ("diverged", "never_settled"):
        d = copy.deepcopy(data)
        d["runs"]["p"]["famcc"]["saturated"][flag] = True
        assert ("p", "saturated", flag) in {
            (x["case"], x["condition"], x["metric"]) for x in cmp.losses(d)
        }
    # a diverged peer scores 0 and cannot beat famcc
    d = copy.deepcopy(data)
    d["runs"]["p"]["adrc"]["nominal"].update(diverged=True, iae=1e-9)
    assert cmp.losses(d) == [] and cmp.radar_scores(d, "p")["adrc"]["accuracy"] == 0.0
    d["runs"]["p"]["lmcc"]["nominal"]["final_rms"] = 0.001
    s = cmp.radar_scores(d, "p")
    assert s["lmcc"]["accuracy"] == 1.0 and s["famcc"]["accuracy"] == 0.0


def test_every_controller_is_built_from_its_space():
    for case in cmp.cases():
        for kind in cmp.controllers():
            sp = cmp.space(kind, case)
            for corner in (0.0, 1.0):
                ctrl = cmp.build(kind, sp.params([corner] * sp.dims), 1e-3, case.limits[0])
                assert ctrl.order == case.order and ctrl.dt == 1e-3


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="kind"):
        cmp.space("lqr", cmp.cases()[0])
    with pytest.raises(ValueError, match="condition"):
        cmp.condition_of("rain")
    with pytest.raises(ValueError, match="family"):
        cmp.famcc_candidates(None, 1e-3, order=2, family="pid", band=0.1, gain=1.0, hold=1.0)
    assert cli.main(["compare", "--out", "/tmp/never", "--plant", "bicycle", "--quiet"]) == 2


def test_the_slower_observer_is_the_documented_factor():
    from famcc.compare.spaces import SLOWER_OBSERVER

    for case in cmp.cases():
        sp = cmp.space("famcc", case)
        u = sp.unit(sp.default)
        slow = sp.slowed(u)
        assert slow is not None
        p, q = sp.params(u), sp.params(slow)
        if "obs_mu" in p:
            assert q["obs_mu"] == pytest.approx(SLOWER_OBSERVER * p["obs_mu"])
        else:
            assert q["obs_ratio"] == pytest.approx(max(p["obs_ratio"] / SLOWER_OBSERVER, 2.0))
        # everything else unchanged
        assert {k: v for k, v in q.items() if not k.startswith("obs")} == pytest.approx(
            {k: v for k, v in p.items() if not k.startswith("obs")}
        )
        # at the slow end of the range there is nothing slower
        name = "obs_mu" if "obs_mu" in p else "obs_ratio"
        end = sp.ranges[name][1] if name == "obs_mu" else sp.ranges[name][0]
        assert sp.slowed(sp.unit({**p, name: end})) is None
    assert cmp.space("adrc", cmp.cases()[0]).slowed(np.array([0.5, 0.5])) is None


def _noise_check(objective, starts):
    """famcc's noise check on example 1 with a fake pool: ``objective(u, noisy) -> J``;
    ``starts``: the nominal history's points. Returns (chosen point, noisy objectives,
    history, tasks run)."""
    from famcc.compare import tuning

    case = cmp.cases()[0]
    sp = cmp.space("famcc", case)
    key = (case.name, "famcc")
    tasks_run = []

    class Pool:
        def map(self, tasks):
            tasks_run.extend(tasks)
            return [
                {
                    **t,
                    "metrics": {
                        "objective": float(objective(np.array(t["u"]), t["condition"] != "nominal"))
                    },
                }
                for t in tasks
            ]

    hist = {key: [(u, float(objective(u, False)), {}) for u in starts]}

    def tasks_for(points, condition="nominal"):
        return [
            {"case": k[0], "kind": k[1], "u": u.tolist(), "condition": condition}
            for k, us in points.items()
            for u in us
        ]

    def record(results):
        for r in results:
            hist[(r["case"], r["kind"])].append((np.array(r["u"]), r["metrics"]["objective"], {}))

    chosen, noisy = tuning._noise_checked(Pool(), hist, {key: [sp]}, tasks_for, record)
    return chosen[key][0], noisy[key], hist[key], tasks_run, sp


def test_the_noise_check_chooses_the_slower_observer_when_noise_rewards_it():
    """J = the first coordinate, plus 3 (1 - the observer's coordinate) under noise."""
    from famcc.compare import tuning

    def objective(u, noisy):
        return u[0] + (3.0 * (1.0 - u[-1]) if noisy else 0.0)

    best = np.full(6, 0.1)
    chosen, noisy, hist, tasks, sp = _noise_check(objective, [best, np.full(6, 0.3)])
    assert len(tasks) == tuning.NOISE_CHECKS["famcc"] == 3
    # the slower observer pays less under noise here: it is chosen
    assert np.array_equal(chosen, sp.slowed(best))
    assert len(noisy) == 2 and len(hist) == 3


def test_the_noise_check_weighs_relative_changes_not_the_noisy_scale():
    """Nominal 0.1 -> 2.0 (20x worse) for a noisy 100 -> 60: the slower candidate is
    not chosen (the product rule; a sum would follow the noisy run's larger scale)."""

    def objective(u, noisy):
        x = u[-1] - 0.1
        return 100.0 - 133.0 * x if noisy else 0.1 + 6.3 * x

    best = np.full(6, 0.1)
    chosen, noisy, hist, _, _ = _noise_check(objective, [best])
    assert noisy[1] < noisy[0]  # the slower one is better under noise
    assert hist[1][1] > 10 * hist[0][1]  # and far worse nominally
    assert np.array_equal(chosen, best)
