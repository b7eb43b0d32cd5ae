# SPDX-License-Identifier: MIT
"""Context, fit, error_of: a fit from Python equals `brdffit fit --json` on the
same table to the last digit."""

import json
import subprocess

import numpy as np
import pytest


def cli_fit(cli, table, *args):
    out = subprocess.run([cli, "fit", table, "--json", *args], check=True,
                         capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines() if line.strip()]


@pytest.mark.parametrize("model, cutoff, scale, options, flags", [
    ("cook-torrance", None, "standard", {}, []),
    ("ward", 70, "flat", {"starts": 4}, ["--cutoff", "70", "--scale", "flat", "--starts", "4"]),
])
def test_fit_equals_the_program(brdffit, ctx, cli, alum_bronze, model, cutoff, scale, options,
                                flags):
    s = brdffit.Samples(brdffit.Table.read(alum_bronze), cutoff=cutoff, scale=scale)
    r = brdffit.fit(ctx, s, model, **options)
    [rec] = cli_fit(cli, alum_bronze, "--model", model, *flags)
    assert rec["status"] == "ok" and rec["model"] == model
    assert rec["backend"] == r.backend == ctx.backend
    # the same doubles, bit for bit (the program prints %.17g)
    assert r.params.d.tolist() == rec["d"]
    assert r.params.s.tolist() == rec["s"]
    assert r.params.p.tolist() == rec["p"]
    assert r.error == rec["error"]
    assert (r.iterations, r.passes, r.cminpack_info, r.samples) == \
        (rec["iterations"], rec["passes"], rec["cminpack_info"], rec["samples"])
    assert rec["settings"]["scale"] == scale and rec["settings"]["metric"] == "ngan-l2"
    assert rec["kind"] == "fit" and rec["status_code"] == 0 and rec["message"] == ""
    assert r.status == brdffit.Status.OK and r.converged
    assert r.model is brdffit.model(model) and r.seconds > 0
    assert 0 <= r.seconds_solver <= r.seconds and 0 <= r.seconds_passes <= r.seconds
    assert 0 <= r.seconds_build <= r.seconds
    # the Error of the fitted parameters is the fit's Error
    assert brdffit.error_of(ctx, s, model, r) == r.error
    assert brdffit.error_of(ctx, s, model, r.params.vector()) == r.error


def test_fit_recovers_a_synthetic_table(brdffit, ctx):
    truth = [0.1, 0.2, 0.3, 0.5, 0.4, 0.3, 0.2, 0.15]
    s = brdffit.Samples(brdffit.Table.from_model("cook-torrance", truth))
    r = brdffit.fit(ctx, s, "cook-torrance")
    assert r.error < 1e-6
    assert np.allclose(r.params.vector(), truth, rtol=1e-4)
    assert brdffit.error_of(ctx, s, "cook-torrance", truth) < 1e-12


def test_host_context(brdffit, alum_bronze):
    with brdffit.Context(backend="host") as host:
        assert host.backend == "host" and host.description.startswith("host")
        assert "brdffit.Context host" in repr(host)
        s = brdffit.Samples(brdffit.Table.read(alum_bronze))
        r = brdffit.fit(host, s, "ward", starts=2, max_evals=50)
        assert r.backend == "host" and r.error > 0
    assert repr(host) == "<brdffit.Context closed>"
    with pytest.raises(brdffit.InvalidArgumentError, match="closed"):
        host.backend
    host.close()  # twice is harmless


def test_context_and_fit_errors(brdffit, ctx, alum_bronze):
    assert ctx.backend in ("opencl", "host") and ctx.description
    with pytest.raises(brdffit.InvalidArgumentError, match="backend"):
        brdffit.Context(backend="gpu")
    with pytest.raises(brdffit.NoDeviceError) as e:
        brdffit.Context(backend="opencl", device="no-such-device-anywhere")
    assert e.value.status == brdffit.Status.NO_DEVICE and "no-such-device-anywhere" in str(e.value)
    s = brdffit.Samples(brdffit.Table.read(alum_bronze))
    with pytest.raises(TypeError, match="unknown option 'stars'"):
        brdffit.fit(ctx, s, "ward", stars=3)
    with pytest.raises(brdffit.InvalidArgumentError, match="starts"):
        brdffit.fit(ctx, s, "ward", starts="many")
    with pytest.raises(brdffit.InvalidArgumentError, match="lambda_um"):
        brdffit.fit(ctx, s, "he", lambda_um=[0.5, 0.4])
    with pytest.raises(brdffit.InvalidArgumentError):
        brdffit.fit(ctx, s, "ward", starts=-3)
    with pytest.raises(brdffit.InvalidArgumentError, match="Context"):
        brdffit.fit(None, s, "ward")
    with pytest.raises(brdffit.InvalidArgumentError, match="Samples"):
        brdffit.error_of(ctx, None, "ward", [0] * 7)
    with pytest.raises(brdffit.UnknownModelError):
        brdffit.fit(ctx, s, "phong")
    with pytest.raises(brdffit.ParamRangeError):
        brdffit.error_of(ctx, s, "ward", [0.1] * 6 + [-1.0])


def test_fit_under_a_metric_equals_the_program(brdffit, ctx, cli, alum_bronze):
    """metric="log": the program's --metric log fit to the last digit, its
    Errors under every metric, error_of under each metric the same."""
    s = brdffit.Samples(brdffit.Table.read(alum_bronze), cutoff=40)
    r = brdffit.fit(ctx, s, "ward", metric="log", starts=2)
    [rec] = cli_fit(cli, alum_bronze, "--model", "ward", "--cutoff", "40", "--starts", "2",
                    "--metric", "log")
    assert rec["settings"]["metric"] == "log" and r.metric == "log"
    assert r.params.vector().tolist() == rec["d"] + rec["s"] + rec["p"]
    assert r.error == rec["error"] == r.errors["log"]
    assert r.errors == rec["errors"]
    assert r.metric_iterations >= 1
    for name in brdffit.METRICS:
        assert brdffit.error_of(ctx, s, "ward", r, metric=name) == pytest.approx(
            r.errors[name], rel=1e-12)
    base = brdffit.fit(ctx, s, "ward", starts=2)
    assert base.metric == "ngan-l2" and base.metric_iterations == 0
    assert base.errors == {"ngan-l2": base.error, "log": None, "cube-root": None}
    every = brdffit.fit(ctx, s, "ward", starts=2, all_errors=True)
    assert every.params == base.params and every.errors["ngan-l2"] == base.error
    assert r.errors["log"] < every.errors["log"]
    for name in brdffit.METRICS:
        assert brdffit.error_of(ctx, s, "ward", every, metric=name) == pytest.approx(
            every.errors[name], rel=1e-12)
    [plain] = cli_fit(cli, alum_bronze, "--model", "ward", "--cutoff", "40", "--starts", "2")
    assert plain["errors"] == base.errors
    [full] = cli_fit(cli, alum_bronze, "--model", "ward", "--cutoff", "40", "--starts", "2",
                     "--errors", "all")
    assert full["errors"] == every.errors and full["d"] + full["s"] + full["p"] == plain["d"] + plain["s"] + plain["p"]


def test_unknown_metric_refused(brdffit, ctx):
    s = brdffit.Samples(brdffit.Table.from_model("ward", [0.1] * 6 + [0.2]), cutoff=30)
    with pytest.raises(brdffit.InvalidArgumentError, match="unknown metric 'l1'"):
        brdffit.fit(ctx, s, "ward", metric="l1")
    with pytest.raises(brdffit.InvalidArgumentError, match="metrics: ngan-l2, log, cube-root"):
        brdffit.error_of(ctx, s, "ward", [0.1] * 6 + [0.2], metric=2)
    assert brdffit.error_of(ctx, s, "ward", [0.1] * 6 + [0.2], metric="cube_root") < 1e-12
