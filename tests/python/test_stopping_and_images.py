"""What a render gives back besides its image, and what a stopped render gives back: progress
for every integrator (chains too), Ctrl-C during the chains, the note a stopped render's image
carries, the images on the way (on_pass) and the other images a render makes (Result.images).

Run by scripts/test.sh with the other Python tests (PYTHONPATH=build/python).
"""

import _thread
import os
import pathlib
import re
import subprocess

import numpy as np
import pytest

import erpt

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("ERPT_BUILD_DIR", ROOT / "build"))
DEFAULT_SCENE = ROOT / "scenes" / "default" / "scene.xml"

# Options under which each integrator takes a second or so at 64x64 (the chains, not the
# seeds, take most of it).
WORK = {
    "path": {"spp": 128},
    "direct": {"spp": 128},
    "bdpt": {"spp": 48},  # its batches hold 65536 samples: three of them
    "erpt": {"spp": 16, "mutations_per_pixel": 128},
    "pmc-er": {"spp": 16},
    "mlt": {"spp": 128},
}


@pytest.fixture(scope="module")
def scene():
    return erpt.load_scene(str(DEFAULT_SCENE))


def flags(options):
    out = []
    for k, v in options.items():
        out += ["--" + k.replace("_", "-"), str(v)]
    return out


@pytest.mark.parametrize("integrator", sorted(WORK))
def test_progress_goes_with_the_work_for_every_integrator(integrator, tmp_path):
    # The CLI prints a line at every tenth of the work it is told of (stderr is not a terminal
    # here), so the count does not depend on the machine's speed: a render that reports only at
    # its end (ERPT's chains and MLT before) prints one line.
    r = subprocess.run([str(BUILD / "erpt"), "render", str(DEFAULT_SCENE), "--integrator", integrator, "--width", "64",
                        "--height", "64", *flags(WORK[integrator]), "-o", str(tmp_path / "out.exr")],
                       capture_output=True, text=True)
    lines = re.findall(r"^progress: (\d+)%", r.stderr, re.M)
    percents = [int(p) for p in lines]
    assert percents == sorted(percents)
    assert len(percents) >= 3, r.stderr


def test_progress_in_python_is_monotone_and_reaches_the_chains(scene):
    seen = []
    erpt.render(scene, "mlt", width=64, height=64, seed=1, progress=seen.append, **WORK["mlt"])
    assert seen == sorted(seen) and all(0 <= f <= 1 for f in seen)
    # MLT's bootstrap is a small part of its work: progress beyond it means the chains report.
    assert any(0.3 < f < 1 for f in seen), seen


def interrupt_at(fraction):
    """A progress callback that presses Ctrl-C once the render is `fraction` done."""
    state = {"sent": False}

    def progress(f):
        if f >= fraction and not state["sent"]:
            state["sent"] = True
            _thread.interrupt_main()

    return progress


@pytest.mark.parametrize("integrator", ["erpt", "pmc-er", "mlt"])
def test_ctrl_c_in_the_chains_returns_their_energy(scene, integrator, tmp_path):
    options = dict(width=64, height=64, seed=3, **WORK[integrator])
    whole = erpt.render(scene, integrator, **options)
    stopped = erpt.render(scene, integrator, progress=interrupt_at(0.5), **options)
    s = stopped.stats
    assert s["partial"] is True
    # Stopped in its first group of passes (ERPT, PMC-ER) or in its chains (MLT): no pass is
    # complete, and the image holds the work done.
    assert s["spp"] == 0 and 0 < s["kept_spp"]
    assert s["mutations"] < whole.stats["mutations"]
    assert "stopped by an interrupt" in s["partial_note"] and "remaining energy" in s["partial_note"]
    # Every chain left deposited the energy it still held: the image is as bright as the whole
    # render's, only noisier (its mean within a few per cent; a render that dropped the chains
    # in flight, or normalised by the work begun, would be far off).
    ratio = stopped.image.mean() / whole.image.mean()
    assert 0.85 < ratio < 1.15, ratio
    assert np.isfinite(stopped.image).all()
    # The note is in the written image's metadata (an EXR header attribute).
    stopped.write(tmp_path / "stopped.exr")
    assert s["partial_note"].encode() in (tmp_path / "stopped.exr").read_bytes()


def test_a_stopped_time_budgeted_render_says_what_it_holds(scene):
    result = erpt.render(scene, "path", width=64, height=64, time=60, progress=interrupt_at(0.005))
    s = result.stats
    assert s["partial"] is True and s["spp"] > 0
    # Not "79 of 32 samples per pixel": a budget has no sample count to be a part of.
    assert re.match(r"%d samples per pixel in %d passes, stopped [0-9.]+ s into a 60 s budget" % (s["spp"], s["passes"]),
                    s["partial_note"]), s["partial_note"]


def test_a_stopped_render_of_fixed_spp_says_how_many_passes_it_holds(scene):
    result = erpt.render(scene, "path", width=64, height=64, spp=100000, progress=interrupt_at(0.0005))
    s = result.stats
    assert s["partial"] is True and 0 < s["spp"] < 100000 and s["kept_spp"] == 0
    assert s["partial_note"] == "%d of 100000 samples per pixel (stopped by an interrupt)" % s["spp"]


@pytest.mark.parametrize("integrator,options", [
    ("path", {"spp": 64}),
    ("erpt", {"spp": 48, "mutations_per_pixel": 16}),
])
def test_on_pass_gets_the_image_after_every_group_of_passes(scene, integrator, options):
    got = []
    result = erpt.render(scene, integrator, width=97, height=61, seed=2,
                         on_pass=lambda image, spp, seconds: got.append((image.copy(), spp, seconds)), **options)
    spps = [spp for _, spp, _ in got]
    # 97 x 61 pixels: groups of 22 passes (131072 samples each at least).
    assert spps == [22, 44, options["spp"]]
    assert [t for _, _, t in got] == sorted(t for _, _, t in got)
    assert np.array_equal(got[-1][0], result.image)
    assert all(image.shape == (61, 97, 3) for image, _, _ in got)


def test_on_pass_with_a_time_budget_and_where_there_are_no_passes(scene):
    got = []
    erpt.render(scene, "path", width=32, height=32, time=0.3, on_pass=lambda image, spp, t: got.append(spp))
    assert len(got) >= 2 and got == sorted(got)
    with pytest.raises(erpt.Error, match="on_pass needs a time budget"):
        erpt.render(scene, "mlt", width=8, height=8, spp=4, on_pass=lambda *a: None)
    with pytest.raises(erpt.Error, match="on_pass must be callable"):
        erpt.render(scene, "path", width=8, height=8, spp=1, on_pass=3)


def test_every_image_a_render_makes_is_in_the_result(scene, tmp_path):
    options = dict(width=45, height=37, seed=5, spp=4, mutations_per_pixel=32)
    r = erpt.render(scene, "erpt", chain_maps=True, pm_filter=True, **options)
    assert sorted(r.images) == ["acceptance", "chains", "mutations", "proposals", "raw"]
    mutations, acceptance = r.images["mutations"][..., 0], r.images["acceptance"][..., 0]
    # Proposals counted at their film positions: at most every chain step (some leave the film).
    assert 0.8 * r.stats["mutations"] < mutations.sum() <= r.stats["mutations"]
    assert np.array_equal(mutations, np.round(mutations))
    assert ((acceptance >= 0) & (acceptance <= 1)).all() and (acceptance[mutations == 0] == 0).all()
    accepted = sum(r.stats["accepted"].values()) / r.stats["mutations"]
    mean_q = (acceptance * mutations).sum() / mutations.sum()
    assert abs(mean_q - accepted) < 0.05, (mean_q, accepted)  # q is the acceptance's expectation
    # The CLI writes the same images beside OUT.exr.
    out = tmp_path / "cli.exr"
    cli = subprocess.run([str(BUILD / "erpt"), "render", "-q", str(DEFAULT_SCENE), "--integrator", "erpt",
                          "--chain-maps", "--pm-filter", *flags(options), "-o", str(out)], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    for name, image in r.images.items():
        assert np.array_equal(erpt.read_image(tmp_path / ("cli-%s.exr" % name)), image), name
    assert not (tmp_path / "cli-mutations.png").exists()  # counts: EXR only

    pmc = erpt.render(scene, "pmc-er", width=45, height=37, seed=5, spp=4, chain_maps=True)
    assert sorted(pmc.images) == ["acceptance", "mutations", "strategy"]
    mlt = erpt.render(scene, "mlt", width=45, height=37, seed=5, spp=8, chain_maps=True)
    assert sorted(mlt.images) == ["acceptance", "mutations"]
    assert erpt.render(scene, "path", width=8, height=8, spp=1).images == {}
    with pytest.raises(erpt.Error, match="chain-maps"):
        erpt.render(scene, "path", width=8, height=8, spp=1, chain_maps=True)
