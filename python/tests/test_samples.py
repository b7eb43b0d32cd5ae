# SPDX-License-Identifier: MIT
"""Samples: counts, options, single samples as the C library gives them."""

import ctypes

import numpy as np
import pytest


def test_counts_and_options(brdffit, alum_bronze):
    t = brdffit.Table.read(alum_bronze)
    s = brdffit.Samples(t)
    assert len(s) == s.count > 900000
    assert s.cutoff == 80.0 and s.scale == "standard"
    assert s.count + s.masked + s.beyond_cutoff == 90 * 90 * 180
    narrow = brdffit.Samples(t, cutoff=60, scale="flat")
    assert narrow.cutoff == 60.0 and narrow.scale == "flat"
    assert narrow.count < s.count and narrow.masked == s.masked
    assert "samples, cutoff 60 deg, scale flat" in repr(narrow)


def test_samples_equal_the_c_samples(brdffit, cdll, alum_bronze):
    from brdffit import _abi

    t = brdffit.Table.read(alum_bronze)
    s = brdffit.Samples(t, scale="flat")
    del t  # the samples do not need the table
    for index in (0, 1, 777, s.count - 1):
        c = _abi.Sample()
        assert cdll.brdffit_samples_get(s._h.ptr, index, ctypes.byref(c), None) == 0
        py = s[index]
        assert py.wi == tuple(c.wi) and py.wo == tuple(c.wo) and py.rgb == tuple(c.rgb)
        assert py.weight == c.weight and py.bin == (c.i, c.j, c.k)
        assert abs(np.linalg.norm(py.wi) - 1) < 1e-12 and py.weight > 0
    assert s[-1] == s[s.count - 1]
    with pytest.raises(IndexError):
        s[s.count]
    with pytest.raises(IndexError):
        s[-s.count - 1]
    with pytest.raises(TypeError):
        s[1.0]


def test_bad_samples(brdffit):
    t = brdffit.Table.zeros()
    for cutoff in (0, 95, float("nan")):
        with pytest.raises(brdffit.InvalidArgumentError, match="cutoff"):
            brdffit.Samples(t, cutoff=cutoff)
    with pytest.raises(brdffit.InvalidArgumentError, match="scale"):
        brdffit.Samples(t, scale="loud")
    with pytest.raises(brdffit.InvalidArgumentError, match="Table"):
        brdffit.Samples("alum-bronze.binary")
    masked = brdffit.Table.from_array(-np.ones((3, 90, 90, 180)))
    with pytest.raises(brdffit.NoSamplesError) as e:
        brdffit.Samples(masked)
    assert e.value.status == brdffit.Status.NO_SAMPLES and "masked" in str(e.value)


def test_prepare(brdffit, ctx):
    """prepare() for some models, all models, again: the set is unchanged
    and a fit of it is the fit of a fresh set, to the bit; bad models refused."""
    t = brdffit.Table.from_model("ward-duer", [0.05, 0.04, 0.03, 0.04, 0.03, 0.02, 0.15])
    fresh, prepared = brdffit.Samples(t, cutoff=60), brdffit.Samples(t, cutoff=60)
    assert prepared.prepare("ggx", 1) is prepared
    prepared.prepare()
    prepared.prepare(brdffit.model("he"))
    assert prepared.count == fresh.count and prepared[100] == fresh[100]
    a = brdffit.fit(ctx, fresh, "ggx")
    b = brdffit.fit(ctx, prepared, "ggx")
    assert a.error == b.error and a.params == b.params and a.passes == b.passes
    with pytest.raises(brdffit.UnknownModelError):
        prepared.prepare("nonesuch")
    with pytest.raises(brdffit.UnknownModelError):
        prepared.prepare(99)


def test_release_memory(brdffit):
    """A freed table's and sample set's large arrays are kept by the library
    for the next ones; release_memory() hands them back once."""
    import gc

    brdffit.release_memory()
    t = brdffit.Table.zeros()
    s = brdffit.Samples(t)
    assert s.count > 0
    del t, s
    gc.collect()
    released = brdffit.release_memory()
    assert released >= 90 * 90 * 180 * 3 * 8  # the table's values at least
    assert brdffit.release_memory() == 0
