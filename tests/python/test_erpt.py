"""The Python module (python/erpt, src/python/module.cpp): its API, bit-identity with the CLI,
errors, the GIL released during renders, interrupts, progress, comparisons and plots.

Run by scripts/test.sh after the C++ suites:
    PYTHONPATH=build/python python3 -m pytest tests/python
"""

import _thread
import json
import os
import pathlib
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import erpt
import erpt.plot

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("ERPT_BUILD_DIR", ROOT / "build"))
CLI = BUILD / "erpt"
DEFAULT_SCENE = ROOT / "scenes" / "default" / "scene.xml"


@pytest.fixture(scope="module")
def scene():
    return erpt.load_scene(str(DEFAULT_SCENE))


def cli(*args):
    return subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)


def test_load_scene_and_info(scene):
    info = scene.info()
    assert info["triangles"] > 0
    assert len(info["shapes"]) > 0 and all("type" in s for s in info["shapes"])
    assert len(info["lights"]) >= 1
    assert {m["type"] for m in info["materials"]} >= {"diffuse"}
    assert isinstance(info["warnings"], list)
    assert info["film"] == (512, 512)
    # Scene defaults, as the CLI's -D.
    small = erpt.load_scene(str(DEFAULT_SCENE), defaults={"res": 40, "spp": 3})
    assert small.info()["film"] == (40, 40) and small.info()["spp"] == 3
    assert info["spheres"] == 2
    meshed = erpt.load_scene(str(DEFAULT_SCENE), tessellate_spheres=True).info()
    assert meshed["spheres"] == 0 and meshed["triangles"] > info["triangles"]


def test_render_gives_an_image_and_statistics(scene):
    result = erpt.render(scene, "path", spp=2, width=33, height=21, seed=4)
    image = result.image
    assert image.dtype == np.float32 and image.shape == (21, 33, 3)
    assert np.isfinite(image).all() and image.mean() > 0
    stats = result.stats
    assert stats["spp"] == 2 and stats["samples"] == 33 * 21 * 2 and stats["rays"] > 0
    assert stats["partial"] is False and stats["integrator"] == "path"
    assert "erpt" in erpt.integrators() and "bdpt" in erpt.integrators()


@pytest.mark.parametrize("integrator,options,flags", [
    ("path", {"spp": 3}, ["--spp", "3"]),
    ("erpt", {"spp": 2, "mutations_per_pixel": 8, "lens_radius": 3.5}, ["--spp", "2", "--mutations-per-pixel", "8", "--lens-radius", "3.5"]),
    ("mlt", {"spp": 4, "bidir_mutation": 0.3}, ["--spp", "4", "--bidir-mutation", "0.3"]),
    ("pssmlt", {"spp": 4, "small_step": 0.05}, ["--spp", "4", "--small-step", "0.05"]),
    ("bdpt", {"spp": 2, "filter": "tent"}, ["--spp", "2", "--filter", "tent"]),
])
def test_render_is_bit_identical_to_the_cli(scene, tmp_path, integrator, options, flags):
    out = tmp_path / "cli.exr"
    r = cli("render", "-q", DEFAULT_SCENE, "--integrator", integrator, "--width", 37, "--height", 29, "--seed", 7,
            *flags, "-o", out)
    assert r.returncode == 0, r.stderr
    result = erpt.render(scene, integrator, width=37, height=29, seed=7, **options)
    assert np.array_equal(result.image, erpt.read_image(str(out)))
    # Result.write writes what the CLI writes.
    result.write(str(tmp_path / "py.exr"))
    assert np.array_equal(erpt.read_image(str(tmp_path / "py.exr")), result.image)
    assert (tmp_path / "py.png").exists()


def test_errors_raise_erpt_error_with_the_cli_text(scene, tmp_path):
    assert issubclass(erpt.Error, RuntimeError)
    with pytest.raises(erpt.Error, match=r"no-such-scene\.xml: error: "):
        erpt.load_scene(str(tmp_path / "no-such-scene.xml"))
    bad = tmp_path / "bad.xml"
    bad.write_text('<scene version="0.6.0">\n  <shape type="obj">\n    <string name="filename" value="x.obj"/>\n</scene>\n')
    with pytest.raises(erpt.Error, match=r"bad\.xml:\d+: error: "):
        erpt.load_scene(str(bad))
    with pytest.raises(erpt.Error, match=r"--lens-radius does not apply to --integrator path"):
        erpt.render(scene, "path", spp=1, width=8, height=8, lens_radius=2)
    with pytest.raises(erpt.Error, match=r"--chain-length must be an integer in \[1, "):
        erpt.render(scene, "erpt", spp=1, width=8, height=8, chain_length=0)
    with pytest.raises(erpt.Error, match=r"--mutation-strategy must be"):
        erpt.render(scene, "erpt", spp=1, width=8, height=8, mutation_strategy="sideways")
    with pytest.raises(erpt.Error, match=r"'checkpoint' is an option of the command line only"):
        erpt.render(scene, "path", spp=1, checkpoint="x.ckpt")
    with pytest.raises(erpt.Error, match=r"unknown option 'colour'"):
        erpt.render(scene, "path", spp=1, colour=3)
    with pytest.raises(erpt.Error, match=r"unknown integrator|integrator 'nope'"):
        erpt.render(scene, "nope", spp=1)
    with pytest.raises(erpt.Error, match=r"give --spp or --mutations-per-pixel, not both"):
        erpt.render(scene, "mlt", spp=1, mutations_per_pixel=4)
    with pytest.raises(erpt.Error, match=r"shape \(height, width, 3\)"):
        erpt.diff(np.zeros((4, 4)), np.zeros((4, 4, 3)))


def test_the_gil_is_released_while_rendering(scene):
    ticks = 0
    running = True

    def count():
        nonlocal ticks
        while running:
            ticks += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    # A time budget, so that the render lasts long enough to tell on any machine.
    erpt.render(scene, "path", time=0.5, width=96, height=96)
    seconds = time.perf_counter() - start
    running = False
    t.join()
    # A thread starved of the GIL would tick about once; one that runs ticks every few ms.
    assert seconds > 0.1
    assert ticks > 10 * seconds


def test_keyboard_interrupt_stops_between_passes_and_returns_what_is_done(scene):
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    start = time.perf_counter()
    result = erpt.render(scene, "path", spp=4096, width=128, height=128)
    seconds = time.perf_counter() - start
    timer.cancel()
    assert result.stats["partial"] is True
    assert 0 < result.stats["spp"] < 4096
    assert np.isfinite(result.image).all() and result.image.mean() > 0
    assert seconds < 30


def test_progress_is_reported_and_a_failing_callback_stops_the_render(scene):
    seen = []
    erpt.render(scene, "path", spp=64, width=64, height=64, progress=seen.append)
    # However fast the render, its end is reported.
    assert seen and all(0 <= f <= 1 for f in seen) and seen == sorted(seen) and seen[-1] == 1

    def fail(fraction):
        raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        erpt.render(scene, "path", spp=4096, width=64, height=64, progress=fail)


def test_diff_takes_arrays_and_paths(scene, tmp_path):
    a = erpt.render(scene, "path", spp=1, width=16, height=16, seed=1)
    b = erpt.render(scene, "path", spp=1, width=16, height=16, seed=2)
    same = erpt.diff(a.image, a.image)
    assert same["mse"] == 0 and same["rel_mse"] == 0 and same["nonfinite_pixels"] == 0
    assert same["mean_ratio"] == pytest.approx((1, 1, 1))
    b.write(str(tmp_path / "b.exr"))
    d = erpt.diff(a.image, str(tmp_path / "b.exr"))
    expected = np.mean((a.image.astype(np.float64) - b.image) ** 2)
    assert d["mse"] == pytest.approx(expected, rel=1e-5)
    nan = a.image.copy()
    nan[0, 0, 0] = np.nan
    assert erpt.diff(nan, a.image)["nonfinite_pixels"] == 1


def test_compare_and_its_plot(scene, tmp_path):
    reference = erpt.render(scene, "path", spp=32, width=16, height=16, seed=9).image
    rows = erpt.compare(scene, reference, integrators=["path", ("erpt", {"mutations_per_pixel": 8})], time=0.3,
                        width=16, height=16, spp=1)
    assert [r["integrator"] for r in rows] == ["path", "erpt[--mutations-per-pixel 8]"]
    for r in rows:
        assert r["curve"] and r["rel_mse"] > 0 and r["eff_rel"] > 0 and r["spp"] >= 1
        assert all(p["seconds"] > 0 for p in r["curve"])
    erpt.plot.plot_compare(rows, str(tmp_path / "rows.png"), title="test")
    assert erpt.read_image(str(tmp_path / "rows.png")).shape[1] >= 500


def test_cli_compare_draws_its_plot_through_python(tmp_path):
    reference = tmp_path / "ref.exr"
    assert cli("render", "-q", DEFAULT_SCENE, "--width", 16, "--height", 16, "--spp", 16, "-o", reference).returncode == 0
    out = tmp_path / "cmp"
    r = cli("compare", "-q", DEFAULT_SCENE, "--width", 16, "--height", 16, "--spp", 1, "--reference", reference,
            "--time", 0.2, "--integrators", "path,direct", "--out", out)
    assert r.returncode == 0, r.stderr
    assert "no compare.png" not in r.stderr, r.stderr
    assert erpt.read_image(str(out / "compare.png")).shape[1] >= 500
    report = json.loads((out / "compare.json").read_text())
    assert len(report["results"]) == 2
    # The module's own command line, on the same report.
    p = subprocess.run([sys.executable, "-m", "erpt.plot", str(out / "compare.json"), "-o",
                        str(tmp_path / "again.png")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "again.png").exists()


@pytest.mark.parametrize("script,args", [
    ("convergence.py", ["--time", "0.2", "--size", "16"]),
    ("image_and_error.py", ["--size", "16", "--spp", "1"]),
])
def test_examples_run(tmp_path, script, args):
    out = tmp_path / "out.png"
    env = dict(os.environ, PYTHONPATH=str(BUILD / "python"))
    p = subprocess.run([sys.executable, str(ROOT / "examples" / script), *args, "-o", str(out)], capture_output=True,
                       text=True, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert erpt.read_image(str(out)).shape[1] >= 500


# Common options: wrong types and values the CLI refuses raise erpt.OptionTypeError (a TypeError)
# or erpt.OptionValueError (a ValueError), both erpt.Error, naming the option and its range.
@pytest.mark.parametrize("name, value, error, text", [
    ("spp", "8", erpt.OptionTypeError, r"spp must be an integer in \[1, 16777216\], not '8' \(str\)"),
    ("spp", 8.0, erpt.OptionTypeError, r"spp must be an integer in \[1, 16777216\], not 8\.0 \(float\)"),
    ("spp", True, erpt.OptionTypeError, r"spp must be an integer .* \(bool\)"),
    ("spp", 0, erpt.OptionValueError, r"spp must be an integer in \[1, 16777216\], not 0"),
    ("spp", 2**40, erpt.OptionValueError, r"spp must be an integer in \[1, 16777216\], not 1099511627776"),
    ("width", 0, erpt.OptionValueError, r"width must be an integer in \[1, 65536\], not 0"),
    ("threads", -1, erpt.OptionValueError, r"threads must be an integer in \[0, 1024\]"),
    ("max_depth", -2, erpt.OptionValueError, r"max_depth must be an integer in \[-1, 100000\]"),
    ("seed", -1, erpt.OptionValueError, r"seed must be an integer in \[0, 2\^64 - 1\], not -1"),
    ("seed", 1.5, erpt.OptionTypeError, r"seed must be an integer"),
    ("time", 0, erpt.OptionValueError, r"time must be in \[0\.001, 1e7\] seconds, not 0"),
    ("time", "5", erpt.OptionTypeError, r"time must be a number of seconds"),
    ("filter", "mitchell", erpt.OptionValueError, r"filter must be 'box', 'tent' or 'gaussian', not 'mitchell'"),
])
def test_common_options_are_checked_as_the_cli_checks_them(scene, name, value, error, text):
    assert issubclass(erpt.OptionTypeError, erpt.Error) and issubclass(erpt.OptionTypeError, TypeError)
    assert issubclass(erpt.OptionValueError, erpt.Error) and issubclass(erpt.OptionValueError, ValueError)
    with pytest.raises(error, match=text):
        erpt.render(scene, "path", **{"spp": 1, "width": 8, "height": 8, name: value})
    # The CLI refuses the same value (a number it can parse) with a non-zero exit.
    if isinstance(value, int) and not isinstance(value, bool) and name != "seed":
        flag = "--" + name.replace("_", "-")
        r = cli("render", DEFAULT_SCENE, "-o", "/nonexistent/x.exr", "--width", 8, "--height", 8, flag, value)
        assert r.returncode != 0 and flag in r.stderr + r.stdout


def test_none_leaves_an_option_to_the_scene(scene):
    r = erpt.render(scene, "path", width=8, height=8, spp=None, seed=None, threads=1)
    assert r.stats["spp"] == scene.info()["spp"]


# Without an integrator, render() uses the scene's, as the CLI does.
def test_the_scenes_integrator_is_the_default(tmp_path):
    text = DEFAULT_SCENE.read_text()
    assert '<integrator type="path"' in text or "<integrator" in text
    xml = tmp_path / "s.xml"
    import re
    xml.write_text(re.sub(r'<integrator type="\w+"', '<integrator type="erpt"', text, count=1))
    s = erpt.load_scene(xml, defaults={"res": 32})
    assert s.info()["integrator"] == "erpt"
    r = erpt.render(s, spp=2, seed=3, width=24, height=16, threads=1)
    assert r.stats["integrator"] == "erpt"
    out = tmp_path / "cli.exr"
    c = cli("render", xml, "-o", out, "-D", "res=32", "--spp", 2, "--seed", 3, "--width", 24, "--height", 16, "--threads", 1, "-q")
    assert c.returncode == 0, c.stderr
    assert np.array_equal(r.image, erpt.read_image(out))


def test_paths_warnings_and_missing_folders(tmp_path):
    bad = tmp_path / "w.xml"
    bad.write_text('<scene version="3.0.0"><bsdf type="diffuse" id="m"><float name="colour" value="1"/></bsdf>'
                   '<shape type="sphere"><ref id="m"/></shape></scene>')
    with pytest.warns(erpt.SceneWarning, match="colour"):
        s = erpt.load_scene(bad)  # a pathlib.Path
    r = erpt.render(s, "path", spp=1, width=4, height=4)
    r.write(tmp_path / "out.exr")  # a pathlib.Path
    assert erpt.read_image(tmp_path / "out.exr").shape == (4, 4, 3)
    with pytest.raises(erpt.Error, match=r"the folder '.*missing' does not exist"):
        r.write(tmp_path / "missing" / "out.exr")
    assert not (tmp_path / "missing").exists()


def test_version_and_an_import_under_another_python(tmp_path):
    assert erpt.__version__ and erpt.__version__[0].isdigit()
    # A copy of the package whose compiled part was built for another interpreter.
    import shutil
    package = tmp_path / "erpt"
    shutil.copytree(pathlib.Path(erpt.__file__).parent, package,
                    ignore=lambda d, names: [n for n in names if n.startswith("_erpt") or n.endswith(".so")])
    (package / "_build_info.py").write_text('version = "0"\npython = (2, 7)\ninterpreter = "/usr/bin/python2.7"\n')
    r = subprocess.run([sys.executable, "-c", "import erpt"], capture_output=True, text=True,
                       env={**os.environ, "PYTHONPATH": str(tmp_path)})
    assert r.returncode != 0
    assert "built for Python 2.7 (/usr/bin/python2.7)" in r.stderr, r.stderr


# `pip install .` (pyproject.toml, setup.py) into a venv that sees Debian's numpy: offline, with
# the build tools Debian ships. The compiled part comes from the test's own CMake build
# (ERPT_BUILD_DIR), which the install reuses; the package then imports outside the source tree,
# is known to pip, and uninstalls.
def test_pip_installs_the_package_into_a_venv(tmp_path):
    venv = tmp_path / "v"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    pip = [str(venv / "bin" / "python"), "-m", "pip"]
    env = {**os.environ, "ERPT_BUILD_DIR": str(BUILD), "PIP_NO_INDEX": "1"}
    env.pop("PYTHONPATH", None)
    r = subprocess.run([*pip, "install", "--no-build-isolation", str(ROOT)], capture_output=True, text=True, env=env,
                       cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    check = ("import erpt, pathlib; s = erpt.load_scene(%r, defaults={'res': 8}); "
             "print(erpt.__version__, pathlib.Path(erpt.__file__).parent, erpt.render(s, spp=1).image.shape)" % str(DEFAULT_SCENE))
    r = subprocess.run([str(venv / "bin" / "python"), "-c", check], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith(erpt.__version__ + " " + str(venv)) and "(8, 8, 3)" in r.stdout, r.stdout
    listed = subprocess.run([*pip, "list"], capture_output=True, text=True, env=env).stdout
    assert any(line.split()[:1] == ["erpt"] for line in listed.splitlines()), listed
    r = subprocess.run([*pip, "uninstall", "-y", "erpt"], capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([str(venv / "bin" / "python"), "-c", "import erpt"], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert r.returncode != 0


# A Scene builds its Embree scene at its first render and keeps it: later renders report no
# build time, and the build is never part of `seconds` (nor of a time budget).
def test_the_embree_scene_is_built_once_per_scene():
    s = erpt.load_scene(DEFAULT_SCENE, defaults={"res": 16})
    first = erpt.render(s, "path", spp=1, seed=1)
    second = erpt.render(s, "path", spp=1, seed=1)
    assert first.stats["build_seconds"] > 0
    assert second.stats["build_seconds"] == 0
    assert np.array_equal(first.image, second.image)
    timed = erpt.render(s, "path", time=0.05, seed=2)
    assert timed.stats["build_seconds"] == 0 and timed.stats["spp"] >= 1


# Notebooks: a Result shows as the CLI's PNG, and erpt.tonemap is that PNG's tone mapping.
def test_tonemap_and_the_png_a_notebook_shows(scene, tmp_path):
    r = erpt.render(scene, "path", spp=2, width=12, height=10, seed=4)
    png = r._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    r.write(tmp_path / "cli.png")
    assert png == (tmp_path / "cli.png").read_bytes()
    mapped = erpt.tonemap(r.image)
    assert mapped.dtype == np.uint8 and mapped.shape == (10, 12, 3)
    linear = np.array([[[0.0, 0.0031308, 0.5]], [[1.0, 4.0, np.nan]]], dtype=np.float32)
    assert erpt.tonemap(linear).tolist() == [[[0, 10, 188]], [[255, 255, 0]]]


def test_the_manifold_perturbation_is_an_option_of_the_chain_integrators():
    # A glass sphere's caustic on a floor: paths E D S S L, which the manifold perturbation walks.
    caustic = erpt.load_scene(str(ROOT / "tests" / "data" / "caustic-scene.xml"))
    for integrator, options in (("erpt", {"spp": 2}), ("pmc-er", {"spp": 2}), ("mlt", {"spp": 2})):
        s = erpt.render(caustic, integrator, width=24, height=24, manifold_perturbation=1, **options).stats
        assert s["proposed"].get("manifold", 0) > 0, integrator
        assert s["accepted"]["manifold"] > 0, integrator
        assert set(s["in_place"]) >= {"no mutation applies", "too long: folded tail, nothing before it moves"}
        assert "manifold walk did not converge" in s["rejected"]
    for integrator in ("path", "bdpt", "direct"):
        with pytest.raises(erpt.Error, match=r"--manifold-perturbation does not apply to --integrator " + integrator):
            erpt.render(caustic, integrator, spp=1, width=8, height=8, manifold_perturbation=0.5)
    with pytest.raises(erpt.Error, match=r"--manifold-perturbation must be"):
        erpt.render(caustic, "erpt", spp=1, width=8, height=8, manifold_perturbation=1.5)
