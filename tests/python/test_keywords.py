"""The module's keyword options are read by the command line's own parser: every option of a
command is there, and what the command line refuses (a bad value, two options that exclude each
other, an unknown name) is refused with its message. Run by ctest (suite `python`)."""
import json
import os
import subprocess

import pytest

import canopy

SRC = os.environ.get("CANOPY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
TOMATO = os.path.join(SRC, "grammars", "tomato.yaml")
SMALL = dict(rows=1, per_row=2, steps=8, backend="cpu")


def cli_error(*args):
    r = subprocess.run([os.environ["CANOPY"], *args], capture_output=True, text=True, timeout=120)
    assert r.returncode != 0
    return r.stderr.strip().removeprefix("canopy: error: ")


def test_stand_takes_every_option_of_the_command_line(tmp_path):
    # Resolution tuning, the rotation switch and device memory were not keywords of canopy.stand.
    opts = ["--rows", "2", "--per-row", "3", "--steps", "14", "--backend", "cpu", "--no-random-rotation",
            "--bend-joints", "2", "--resolve-candidates", "3", "--resolve-axes", "6", "--resolve-step", "2",
            "--max-device-memory", "1G", "--jitter", "0.03"]
    assert subprocess.run([os.environ["CANOPY"], "stand", TOMATO, "-o", str(tmp_path / "cli"), *opts],
                          capture_output=True, timeout=300).returncode == 0
    rep = canopy.stand(TOMATO, tmp_path / "py", rows=2, per_row=3, steps=14, backend="cpu", no_random_rotation=True,
                       bend_joints=2, resolve_candidates=3, resolve_axes=6, resolve_step=2, max_device_memory="1G",
                       jitter=0.03)
    want = json.load(open(tmp_path / "cli" / "report.json"))
    assert {**rep["config"], "out": None} == {**want["config"], "out": None}
    for f in ("organs.csv", "plants.csv", "contacts.csv", "contacts_after.csv", "stand.glb"):
        assert (tmp_path / "cli" / f).read_bytes() == (tmp_path / "py" / f).read_bytes(), f


@pytest.mark.parametrize("options, args", [
    (dict(clearance=150), ["--clearance", "150"]),
    (dict(seed=-1), ["--seed", "-1"]),
    (dict(per_row=0), ["--per-row", "0"]),
    (dict(no_resolve=True, max_rounds=3), ["--no-resolve", "--max-rounds", "3"]),
    (dict(glb_instancing=True, formats="ply"), ["--glb-instancing", "--formats", "ply"]),
    (dict(random_rotation=True, no_random_rotation=True), ["--random-rotation", "--no-random-rotation"]),
    (dict(positions=""), ["--positions", ""]),
    (dict(level="twig"), ["--level", "twig"]),
])
def test_stand_refuses_what_the_command_line_refuses(tmp_path, options, args):
    message = cli_error("stand", TOMATO, "--rows", "1", "--per-row", "2", "--steps", "8", *args, "-o", str(tmp_path / "c"))
    with pytest.raises(ValueError) as e:
        canopy.stand(TOMATO, tmp_path / "p", **{**dict(rows=1, per_row=2, steps=8), **options})
    assert str(e.value) == message
    assert not (tmp_path / "p").exists()


def test_keyword_types(tmp_path):
    never = tmp_path / "never"
    with pytest.raises(ValueError, match="stand: no_resolve takes True or False, got 1"):
        canopy.stand(TOMATO, never, no_resolve=1)
    with pytest.raises(ValueError, match="stand: unknown option 'help'"):
        canopy.stand(TOMATO, never, help=True)
    with pytest.raises(ValueError, match="sweep: unknown option 'rowz'"):
        canopy.sweep(TOMATO, never, rowz=2)
    assert not never.exists()
    with pytest.raises(ValueError, match="seed: needs a whole number from 0 to 18446744073709551615, got -1"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, seed=-1)
    with pytest.raises(ValueError, match="got 18446744073709551616"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, seed=2**64)
    with pytest.raises(ValueError, match="got 1.5"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, seed=1.5)
    with pytest.raises(ValueError, match="light: give periodic or no_periodic, not both"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=6).light(periodic=True, no_periodic=True)
    with pytest.raises(ValueError, match="embedded null byte"):
        canopy.Stand.grow(TOMATO + "\0ignored", rows=1, per_row=1)
    with pytest.raises(ValueError, match="embedded null byte"):
        canopy.stand(TOMATO, tmp_path / "nul", positions=str(tmp_path / "p.csv") + "\0junk")
    lit = canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=6).light(periodic=False, no_periodic=True, sky_directions=0,
                                                                      suns=[(60, 180)], error=0.05)
    assert lit["direct"][0]["intercepted_fraction"] >= 0  # the two agree: taken


def test_derive_refuses_a_constant_given_twice():
    """set={"nodes": 3} with nodes=10 took 10 without a word; the command line refuses it."""
    with pytest.raises(ValueError, match="--set nodes: given twice"):
        canopy.derive(TOMATO, set={"nodes": 3}, nodes=10, stats=True)
    with pytest.raises(ValueError, match="--set nodes: given twice \\('3' in set="):
        canopy.derive(TOMATO, set={"nodes": "3"}, nodes=10, stats=True)
    assert canopy.derive(TOMATO, nodes=3, stats=True) == canopy.derive(TOMATO, set={"nodes": 3}, stats=True)


def test_detect_and_resolve_check_as_the_command_line():
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=8)
    with pytest.raises(ValueError, match="--backend: bogus not in"):  # ran as auto
        s.detect(backend="bogus")
    with pytest.raises(ValueError, match="--backend: bogus not in"):
        s.resolve(backend="bogus")
    with pytest.raises(ValueError, match="--clearance: needs a number from 0 to 100, got 150"):  # was taken
        s.detect(clearance=150)
    with pytest.raises(ValueError, match="--resolve-clearance: needs a number from 0 to 100, got 101"):
        s.resolve(resolve_clearance=101)
    with pytest.raises(ValueError, match="Stand.resolve: unknown option 'no_resolve'"):
        s.resolve(no_resolve=True)
    with pytest.raises(ValueError, match="--max-device-memory: .lots. is not a size"):
        s.detect(max_device_memory="lots")
    # Resolution's tuning reaches it: with one joint a chain never bends.
    rep = canopy.Stand.grow(TOMATO, rows=2, per_row=3, steps=14).resolve(backend="cpu", bend_joints=1)
    assert rep["bends"] == 0 and rep["bend_joints"] == 0


def test_light_paths_and_options(tmp_path):
    out = tmp_path / "s"
    canopy.stand(TOMATO, out, **SMALL)
    a = canopy.light(os.fsencode(str(out)), suns=[(60, 180)], sky_directions=4, error=0.01)  # was "b'...'"
    b = canopy.light(out, suns=[(60, 180)], sky_directions=4, error=0.01)
    assert a["direct"] == b["direct"]
    with pytest.raises(TypeError):
        canopy.light(5)
    with pytest.raises(ValueError, match="--rows: .* is a folder that holds a stand already"):
        canopy.light(out, rows=3)
    with pytest.raises(ValueError, match="--rows: Stand.light lights the stand it is called on"):
        canopy.Stand.read(out).light(rows=3)
    lit = canopy.Stand.read(out).light(suns=[(60, 180)], sky_directions=4, error=0.01, periodic=False)
    assert lit["periodic"] is False


def test_grammar_notes_are_warnings(tmp_path):
    typo = tmp_path / "typo.yaml"
    typo.write_text(open(TOMATO).read().replace("\n  L:  {prototype: leaflet", "\n  Lf: {prototype: leaflet"))
    import numpy as np
    for call in (lambda: canopy.derive(typo, steps=2), lambda: canopy.Stand.grow(typo, rows=1, per_row=1, steps=4),
                 lambda: canopy.Stand.grow(typo, positions=np.array([[0, 0, 0, 1.0]]), steps=4),
                 lambda: canopy.stand(typo, tmp_path / "o", **SMALL),
                 lambda: canopy.light(typo, out=tmp_path / "l", sky_directions=0, rays_per_m2=200, **SMALL),
                 lambda: canopy.sweep(typo, tmp_path / "w", steps=[4], rows=1, per_row=2, seeds=1, no_light=True,
                                      backend="cpu")):
        with pytest.warns(UserWarning, match="organ 'Lf' is written by neither the axiom nor any rule"):
            call()


def test_a_stand_that_cannot_fit_is_refused_before_growing():
    with pytest.raises(RuntimeError, match="a stand of 10000000000 plants needs about"):  # was MemoryError
        canopy.Stand.grow(TOMATO, rows=100000, per_row=100000)


def test_values_as_python_holds_them(tmp_path):
    import numpy as np
    # Paths are paths: another type is a TypeError, as for a path argument (out=3 made a folder '3').
    with pytest.raises(TypeError):
        canopy.stand(TOMATO, tmp_path / "a", positions=True)
    with pytest.raises(TypeError):
        canopy.light(TOMATO, out=3, **SMALL)
    assert not (tmp_path / "a").exists() and not os.path.exists("3")
    # Any iterable is a list: a range, a NumPy array (rows of pairs for suns), a set.
    r = canopy.sweep(TOMATO, tmp_path / "w", steps=range(8, 9), plant_spacing=np.array([0.3, 0.4]), rows=1,
                     per_row=2, seeds=1, no_light=True, backend="cpu")
    assert r["total"] == 2
    out = tmp_path / "s"
    canopy.stand(TOMATO, out, collide={"leaflet", "petiole"}, **SMALL)
    a = canopy.light(out, suns=np.array([[60, 180]]), sky_directions=4, error=0.01)
    b = canopy.light(out, suns=[(60, 180)], sky_directions=4, error=0.01)
    assert a["direct"] == b["direct"]
    # NumPy's integers and bools are integers and bools.
    assert canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=4, seed=np.int64(3)).plants["seed"][0] == \
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=4, seed=3).plants["seed"][0]
    rep = canopy.stand(TOMATO, tmp_path / "n", no_resolve=np.bool_(True), **SMALL)
    assert rep["resolution"]["ran"] is False
    with pytest.raises(ValueError, match="seed: needs a whole number"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, seed=np.bool_(True))
    # A NumPy array of no dimensions is one value.
    r = canopy.sweep(TOMATO, tmp_path / "z", steps=np.array(4), seeds=np.array(1), rows=1, per_row=2, no_light=True,
                     backend="cpu")
    assert r["total"] == 1
