"""The canopy Python module against the command line on the same stands, its arrays, its
errors and its callbacks. Run by ctest (suite `python`) with PYTHONPATH at build/python and
CANOPY at the canopy program."""
import filecmp
import gc
import json
import re
import os
import subprocess

import numpy as np
import pytest

import canopy

SRC = os.environ.get("CANOPY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("CANOPY", os.path.join(SRC, "build", "tools", "canopy"))
TOMATO = os.path.join(SRC, "grammars", "tomato.yaml")
ROWS = dict(rows=2, per_row=3, steps=14, random_rotation=True, jitter=0.02, seed=4)
ROW_ARGS = ["--rows", "2", "--per-row", "3", "--steps", "14", "--random-rotation", "--jitter", "0.02", "--seed", "4"]


def cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def test_derive_equals_the_command_line():
    algae = os.path.join(SRC, "grammars", "classic", "algae.yaml")
    assert canopy.derive(algae, steps=7) == cli("derive", algae, "--steps", "7").stdout.strip()
    want = cli("derive", TOMATO, "--steps", "9", "--seed", "5", "--set", "phyllotaxis=100").stdout.strip()
    assert canopy.derive(TOMATO, steps=9, seed=5, set={"phyllotaxis": 100}) == want
    assert canopy.derive(TOMATO, steps=9, seed=5, phyllotaxis=100) == want
    with pytest.raises(ValueError, match="nosuchconstant"):
        canopy.derive(TOMATO, steps=3, nosuchconstant=1)
    stats = canopy.derive(TOMATO, steps=9, stats=True)
    assert stats == json.loads(cli("derive", TOMATO, "--steps", "9", "--stats").stdout)
    # Counts out of range: the command line's refusal as a ValueError (pybind11 raised TypeError).
    for kw, message in [({"seed": -1}, "seed: needs a whole number from 0 to 18446744073709551615, got -1"),
                        ({"seed": 2**64}, "seed: needs a whole number from 0 to"),
                        ({"steps": 2**70}, "steps: needs a whole number from 0 to 100000"),
                        ({"max_modules": 0}, "max_modules: needs a whole number from 1 to")]:
        with pytest.raises(ValueError, match=re.escape(message)):
            canopy.derive(TOMATO, **kw)
    with pytest.raises(TypeError, match="steps: needs an int"):
        canopy.derive(TOMATO, steps=2.5)
    assert canopy.derive(TOMATO, steps=np.int64(5), seed=np.uint64(3)) == canopy.derive(TOMATO, steps=5, seed=3)
    assert canopy.derive(TOMATO, steps=5, seed=2**64 - 1) == cli("derive", TOMATO, "--steps", "5", "--seed", str(2**64 - 1)).stdout.strip()


@pytest.fixture(scope="module")
def cli_stand(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    r = cli("stand", TOMATO, *ROW_ARGS, "--formats", "glb,obj,ply", "--backend", "cpu", "-o", str(out))
    assert r.returncode == 0, r.stderr
    return out


FILES = ["stand.glb", "stand.obj", "stand.mtl", "stand.ply", "organs.csv", "plants.csv"]


def test_stand_equals_the_command_line(cli_stand, tmp_path):
    rep = canopy.stand(TOMATO, tmp_path, formats="glb,obj,ply", backend="cpu", **ROWS)
    for f in FILES + ["contacts.csv", "contacts_after.csv"]:
        assert filecmp.cmp(cli_stand / f, tmp_path / f, shallow=False), f
    want = json.load(open(cli_stand / "report.json"))
    for key in ["contacts_before", "contacts_after", "counts", "stand_origin"]:
        assert rep[key] == want[key]
    drop = lambda r: {k: v for k, v in r.items() if k != "rounds"}
    assert drop(rep["resolution"]) == drop(want["resolution"])


def test_step_by_step_equals_the_command_line(cli_stand, tmp_path):
    s = canopy.Stand.grow(TOMATO, **ROWS)
    found = s.detect(backend="cpu")
    before = np.loadtxt(cli_stand / "contacts.csv", delimiter=",", skiprows=1, usecols=(0, 1, 2, 3), dtype=np.int32, ndmin=2)
    got = np.stack([found["contacts"][k] for k in ("organ_a", "organ_b", "plant_a", "plant_b")], axis=1)
    assert np.array_equal(got, before)
    rep = s.resolve(backend="cpu")
    want = json.load(open(cli_stand / "report.json"))["resolution"]
    assert rep["organs_moved"] == want["organs_moved"]
    assert rep["mean_turn_deg"] == want["mean_turn_deg"]
    assert rep["max_turn_deg"] == want["max_turn_deg"]
    s.export(tmp_path, formats=["glb", "obj", "ply"])
    for f in FILES:
        assert filecmp.cmp(cli_stand / f, tmp_path / f, shallow=False), f
    # canopy stand's contact tables: before the resolution and after it (contacts.csv was the last
    # detection, the resolution's after).
    for f in ("contacts.csv", "contacts_after.csv"):
        assert filecmp.cmp(cli_stand / f, tmp_path / f, shallow=False), f
    # Exported again in fewer formats: the meshes of the formats left out go, the folder holds one stand.
    s.export(tmp_path, formats=["ply"])
    assert sorted(p.name for p in tmp_path.glob("stand.*")) == ["stand.ply"]


def test_arrays_shapes_dtypes_and_views(cli_stand):
    s = canopy.Stand.read(str(cli_stand))
    n = s.organ_count
    assert s.organs.shape == (n,)
    assert s.organs.dtype.names == ("plant", "parent", "leaf", "kind", "prototype", "lod", "reserved")
    assert s.organs.dtype.itemsize == 16
    assert s.transforms.shape == (n, 4, 3) and s.transforms.dtype == np.float32
    assert s.base_points.shape == (n, 3) and s.base_points.dtype == np.float32
    assert s.area.shape == (n,) and s.length.shape == (n,)
    assert np.array_equal(s.ids, table_ids(cli_stand))
    assert np.array_equal(s.base_points, s.transforms[:, 3, :])
    # No copies: the arrays view the stand's memory.
    assert not s.transforms.flags.owndata and not s.organs.flags.owndata
    assert np.shares_memory(s.transforms, s.base_points)
    # The same numbers as organs.csv.
    table = np.genfromtxt(cli_stand / "organs.csv", delimiter=",", names=True, dtype=None, encoding=None)
    assert np.array_equal(s.organs["plant"], table["plant"])
    assert np.array_equal(s.organs["parent"], table["parent"])
    assert np.array_equal(s.organs["leaf"], table["leaf"])
    assert [canopy.KINDS[k] for k in s.organs["kind"]] == list(table["kind"])
    assert np.allclose(s.area, table["area"], rtol=1e-9)
    assert np.array_equal(s.transforms[:, 3, 0], table["tx"].astype(np.float32))
    assert s.plants.shape == (s.plant_count,) and s.plants["organ_count"].sum() == n


def table_ids(folder):
    return np.genfromtxt(folder / "organs.csv", delimiter=",", names=True, dtype=None, encoding=None)["id"]


def test_a_view_keeps_its_stand_alive():
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=12)
    t, o = s.transforms, s.organs
    want = t.copy()
    del s
    gc.collect()
    _ = [canopy.Stand.grow(TOMATO, rows=1, per_row=3, steps=12) for _ in range(3)]  # reuse freed memory, if any
    assert np.array_equal(t, want)
    assert o["plant"].max() == 1


def test_errors_carry_the_located_message(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("axiom: A(1\nproductions: []\n")
    message = cli("derive", str(bad)).stderr.strip().removeprefix("canopy: error: ")
    with pytest.raises(ValueError) as e:
        canopy.derive(str(bad))
    assert str(e.value) == message
    assert ":1:" in message
    with pytest.raises(FileNotFoundError, match="cannot open the grammar file"):
        canopy.Stand.grow(str(tmp_path / "missing.yaml"))
    with pytest.raises(FileNotFoundError, match="cannot open the positions file"):
        canopy.stand(TOMATO, tmp_path / "o", positions=str(tmp_path / "missing.csv"))
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=10)
    with pytest.raises(ValueError, match="level"):
        s.detect(level="twig")
    with pytest.raises(ValueError, match="unknown organ kind 'root'"):
        s.detect(collide="leaflet,root")
    with pytest.raises(ValueError, match="--clearance: needs a finite number, got nan"):
        s.detect(clearance=float("nan"))
    with pytest.raises(ValueError, match="--resolve-clearance: needs a finite number, got inf"):
        s.resolve(resolve_clearance=float("inf"))
    with pytest.raises(ValueError, match="--clearance: needs a finite number, got nan"):
        canopy.stand(TOMATO, tmp_path / "nan", rows=1, per_row=2, steps=10, clearance=float("nan"))
    assert not any((tmp_path / "nan").glob("*"))
    with pytest.raises(ValueError, match="N x 4"):
        canopy.Stand.grow(TOMATO, positions=np.zeros((2, 3)))
    with pytest.raises(ValueError, match="plant 1: its position and rotation must be finite numbers"):
        canopy.Stand.grow(TOMATO, positions=np.array([[0, 0, 0, 1], [float("nan"), 0, 0, 2]]), steps=5)
    with pytest.raises(ValueError, match="plant 0: its position and rotation must be finite"):
        canopy.Stand.grow(TOMATO, positions=np.array([[0, 0, float("inf"), 1]]), steps=5)
    with pytest.raises(ValueError, match="the level of detail must lie in 1..16"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, lod=0)
    with pytest.raises(ValueError, match="the derivation steps must lie in 0..100000"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=-1)
    with pytest.raises(ValueError, match="the thread count must be at least 0"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, threads=-3)
    for seed in (1.5, 2.0**70, -1):
        with pytest.raises(ValueError, match="row 0: the seed must be a non-negative integer below 2\\^64"):
            canopy.Stand.grow(TOMATO, positions=np.array([[0, 0, 0, seed]]), steps=5)
    with pytest.raises(ValueError, match="unknown option 'rowz'"):
        canopy.stand(TOMATO, tmp_path / "o", rowz=3)
    with pytest.raises(ValueError, match="is empty"):
        canopy.sweep(TOMATO, tmp_path / "w", plant_spacing="0.5:0.3:0.1")


def test_positions_array_equals_a_positions_file(tmp_path):
    pos = np.array([[0, 0, 30, 7], [0.35, 0.1, 200, 8], [0.7, 0, 90, 9]], dtype=float)
    (tmp_path / "p.csv").write_text("x,y,rotation,seed\n" + "".join(f"{a},{b},{c},{int(d)}\n" for a, b, c, d in pos))
    assert cli("stand", TOMATO, "--positions", str(tmp_path / "p.csv"), "--steps", "12", "--backend", "cpu", "--no-resolve",
               "-o", str(tmp_path / "cli")).returncode == 0
    s = canopy.Stand.grow(TOMATO, positions=pos, steps=12)
    s.export(tmp_path / "py")
    for f in ["stand.glb", "organs.csv", "plants.csv"]:
        assert filecmp.cmp(tmp_path / "cli" / f, tmp_path / "py" / f, shallow=False), f


def test_positions_seeds_stay_the_whole_numbers_given(tmp_path):
    """canopy's own seeds (plants.csv) are 63-bit: a float64 array rounded them to other plants
    (3395948882924712079 grew as ...936, 321 organs instead of 318), silently."""
    seed = 3395948882924712079
    (tmp_path / "p.csv").write_text(f"x,y,rotation,seed\n0,0,0,{seed}\n")
    assert cli("stand", TOMATO, "--positions", str(tmp_path / "p.csv"), "--steps", "12", "--backend", "cpu", "--no-resolve",
               "-o", str(tmp_path / "cli")).returncode == 0
    for i, given in enumerate([np.array([[0, 0, 0, seed]], dtype=np.uint64), [[0, 0, 0, seed]],
                               np.array([[0.0, 0, 0, seed]], dtype=object)]):
        canopy.Stand.grow(TOMATO, positions=given, steps=12).export(tmp_path / f"py{i}")
        for f in ["organs.csv", "plants.csv"]:
            assert filecmp.cmp(tmp_path / "cli" / f, tmp_path / f"py{i}" / f, shallow=False), (i, f)
    # What NumPy reads as an array (a DataFrame, anything with __array__) is read as np.asarray
    # reads it: rows, not columns (a DataFrame's df[0] is a column).
    class Table:
        def __init__(self, a):
            self.a = a

        def __array__(self, dtype=None, copy=None):
            return self.a

        def __getitem__(self, i):
            return self.a[:, i]

        def __len__(self):
            return 4

    rows = np.array([[0, 0, 0, 1], [1, 0, 10, 2], [2, 0, 20, 3], [3, 0, 30, 4]], dtype=float)
    canopy.Stand.grow(TOMATO, positions=Table(rows), steps=12).export(tmp_path / "table")
    canopy.Stand.grow(TOMATO, positions=rows, steps=12).export(tmp_path / "array")
    assert filecmp.cmp(tmp_path / "table" / "plants.csv", tmp_path / "array" / "plants.csv", shallow=False)
    with pytest.raises(ValueError, match="N x 4"):
        canopy.Stand.grow(TOMATO, positions=np.zeros((0, 3), dtype=int), steps=5)
    with pytest.raises(ValueError, match="row 0: the seed lies past 2\\^53"):
        canopy.Stand.grow(TOMATO, positions=np.array([[0, 0, 0, seed]], dtype=float), steps=5)
    with pytest.raises(ValueError, match="row 0: the seed must be a whole number, not a bool"):
        canopy.Stand.grow(TOMATO, positions=[[0, 0, 0, True]], steps=5)


def test_a_grammar_naming_a_positions_file_grows_those_plants(tmp_path):
    """A grammar whose stand entry names a positions file grows those plants from Python as on
    the command line (Stand.grow took one plant at the origin); the export never replaces the file."""
    (tmp_path / "plants.csv").write_text("x,y,rotation,seed\n0,0,0,1\n0.5,0,90,2\n1,0.2,45,3\n")
    text = open(TOMATO).read()
    lines = [line for line in text.splitlines() if not line.startswith("stand:")]
    assert len(lines) == len(text.splitlines()) - 1  # the entry is one line, replaced here
    (tmp_path / "g.yaml").write_text("\n".join(lines + ["stand: {positions: plants.csv}"]) + "\n")
    grammar = str(tmp_path / "g.yaml")
    s = canopy.Stand.grow(grammar, steps=8)
    assert s.plant_count == 3
    assert not s.ids.flags.writeable  # read-only, as the views
    assert cli("stand", grammar, "--steps", "8", "--no-resolve", "--backend", "cpu", "-o", str(tmp_path / "cli")).returncode == 0
    s.export(tmp_path / "py")
    for f in ["stand.glb", "organs.csv", "plants.csv"]:
        assert filecmp.cmp(tmp_path / "cli" / f, tmp_path / "py" / f, shallow=False), f
    with pytest.raises(ValueError, match="the positions file"):
        s.export(tmp_path)
    s.export(tmp_path / "str", formats="glb")  # one string, as canopy.stand takes it
    assert filecmp.cmp(tmp_path / "cli" / "stand.glb", tmp_path / "str" / "stand.glb", shallow=False)
    with pytest.raises(ValueError, match="formats: give at least one of glb, obj, ply"):
        s.export(tmp_path / "none", formats=[])
    # The exported folder reads back and takes light, with a tile: it holds no report.json (the
    # layout), as a positions stand has no lattice.
    assert canopy.Stand.read(tmp_path / "py").plant_count == 3
    lit = cli("light", str(tmp_path / "py"), "--sun", "60,180", "--error", "0.02", "--tile", "-0.5,-0.5,1.5,0.7")
    assert lit.returncode == 0, lit.stderr
    no_tile = cli("light", str(tmp_path / "py"), "--sun", "60,180")
    assert no_tile.returncode == 2 and "without report.json" in no_tile.stderr
    assert (tmp_path / "plants.csv").read_text().startswith("x,y,rotation,seed\n0,0,0,1\n")
    assert canopy.Stand.grow(grammar, rows=1, per_row=2, steps=8).plant_count == 2  # row options win
    with pytest.raises(ValueError, match="rows: needs a whole number from 1 to 2147483647, got -1"):
        canopy.Stand.grow(TOMATO, rows=-1, per_row=2, steps=4)


def test_compact_glb_equals_the_command_line(tmp_path):
    args = ["--positions", str(tmp_path / "p.csv"), "--steps", "12", "--backend", "cpu", "--no-resolve"]
    (tmp_path / "p.csv").write_text("x,y,rotation,seed\n0,0,30,7\n0.35,0.1,200,8\n")
    assert cli("stand", TOMATO, *args, "--glb-compact", "-o", str(tmp_path / "cli")).returncode == 0
    canopy.stand(TOMATO, tmp_path / "run", positions=str(tmp_path / "p.csv"), steps=12, backend="cpu", no_resolve=True,
                 glb_compact=True)
    s = canopy.Stand.grow(TOMATO, positions=np.array([[0, 0, 30, 7], [0.35, 0.1, 200, 8]], dtype=float), steps=12)
    s.export(tmp_path / "py", glb_compact=True)
    for d in ["run", "py"]:
        assert filecmp.cmp(tmp_path / "cli" / "stand.glb", tmp_path / d / "stand.glb", shallow=False), d
    with pytest.raises(ValueError, match="choose one"):
        s.export(tmp_path / "both", glb_compact=True, glb_instancing=True)
    # A glb form without a glb is refused, as canopy stand refuses it; nothing is written.
    with pytest.raises(ValueError, match=r"glb_compact is a form of stand.glb, and formats ply writes none"):
        s.export(tmp_path / "noglb", formats=["ply"], glb_compact=True)
    with pytest.raises(ValueError, match=r"glb_instancing is a form of stand.glb, and formats obj writes none"):
        s.export(tmp_path / "noglb", formats="obj", glb_instancing=True)
    assert not (tmp_path / "noglb").exists()


def test_a_stand_at_work_refuses_other_calls_on_it(tmp_path):
    # From resolve's own progress callback: detect, resolve, export and light on the stand being
    # resolved are refused (they read or turned organs under the resolution); another stand is free.
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=4, plant_spacing=0.25, steps=16)
    other = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=10)
    refused, free = [], []

    def nested(round_, left, seconds):
        if refused:
            return
        for call in (lambda: s.detect(backend="cpu"), lambda: s.resolve(backend="cpu"),
                     lambda: s.export(tmp_path / "mid"), lambda: s.light(backend="cpu", sky=4)):
            with pytest.raises(RuntimeError, match="in use by Stand.resolve"):
                call()
            refused.append(1)
        free.append(len(other.detect(backend="cpu")["contacts"]) >= 0)

    rep = s.resolve(backend="cpu", progress=nested)
    assert len(refused) == 4 and free == [True]
    assert len(rep["contacts_after"]) == 0
    assert not (tmp_path / "mid").exists()
    s.detect(backend="cpu")  # free again once it returned
    s.export(tmp_path / "after")
    assert (tmp_path / "after" / "organs.csv").exists()


def test_a_callback_that_raises_stops_the_run_cleanly(tmp_path):
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=4, plant_spacing=0.25, steps=16)
    calls = []

    def stop(round_, left, seconds):
        calls.append(round_)
        raise RuntimeError("stop here")

    with pytest.raises(TypeError, match="progress must be callable"):
        s.resolve(backend="cpu", progress=1)
    with pytest.raises(TypeError, match="progress must be callable"):
        canopy.sweep(TOMATO, tmp_path / "never", progress=5, plant_spacing=[0.3], steps=[10], seeds=1, rows=1, per_row=2)
    assert not (tmp_path / "never").exists()
    with pytest.raises(RuntimeError, match="stop here"):
        s.resolve(backend="cpu", progress=stop)
    assert calls == [1]
    assert np.isfinite(s.transforms).all()
    s.detect(backend="cpu")  # still usable
    # A sweep stopped by its callback after one run keeps that run and resumes after it.
    seen = []

    def once(index, total, row):
        seen.append(row["status"])
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        canopy.sweep(TOMATO, tmp_path / "w", progress=once, plant_spacing=[0.3, 0.4], steps=[10], seeds=1, rows=1, per_row=2, backend="cpu")
    assert seen == ["ok"]
    assert len(canopy.sweep_rows(tmp_path / "w")) == 1
    assert len(canopy.sweep_rows(os.fsencode(tmp_path / "w"))) == 1  # bytes, as every path
    left = canopy.sweep(TOMATO, tmp_path / "w", plant_spacing=[0.3, 0.4], steps=[10], seeds=1, rows=1, per_row=2, backend="cpu")
    assert left["ran"] == 1 and len(canopy.sweep_rows(tmp_path / "w")) == 2
    assert left["failed"] == 0 and left["failed_in_table"] == 0
    assert len(canopy.sweep_rows(tmp_path / "w", summary=True)) == 2
    # Every number a float, every empty one nan (a cell of one run has no sd; the turns' empty
    # cells were the string ''), so that the rows make a float array.
    for summary in (False, True):
        rows = canopy.sweep_rows(tmp_path / "w", summary=summary)
        numeric = [k for k in rows[0] if k not in ("status", "backend", "message")]
        assert np.array([[r[k] for k in numeric] for r in rows], dtype=float).shape == (2, len(numeric))
    assert np.isnan(canopy.sweep_rows(tmp_path / "w", summary=True)[0]["lai_sd"])
    with pytest.raises(ValueError, match=r"holds 2 run\(s\) made with other settings \(rows 1 -> 2\)"):
        canopy.sweep(TOMATO, tmp_path / "w", plant_spacing=[0.3, 0.4], steps=[10], seeds=1, rows=2, per_row=2, backend="cpu")


def test_row_options_override_the_grammar_entry_field_by_field(tmp_path):
    """A row keyword changes only that field of the grammar's stand entry, as on the command line;
    every organ kind takes part by default."""
    one = canopy.Stand.grow(TOMATO, per_row=4, steps=6).plants
    full = canopy.Stand.grow(TOMATO, rows=1, per_row=4, row_spacing=1.0, plant_spacing=0.4, jitter=0.02,
                             random_rotation=True, seed=1, steps=6).plants
    assert np.array_equal(one, full)
    assert np.any(one["rotation"] != 0)
    flat = canopy.Stand.grow(TOMATO, per_row=4, steps=6, random_rotation=False).plants
    assert np.all(flat["rotation"] == 0) and np.any(flat["y"] != 0)
    rep = canopy.stand(TOMATO, tmp_path, per_row=4, steps=6, no_resolve=True, backend="cpu")
    sources = rep["config"]["layout"]["sources"]
    assert sources["per_row"] == "command line" and sources["rows"] == sources["jitter"] == sources["seed"] == "grammar"
    assert rep["config"]["collide"] == "all"
    cli_run = cli("stand", TOMATO, "--per-row", "4", "--steps", "6", "--no-resolve", "--backend", "cpu", "-o", str(tmp_path / "c"))
    assert cli_run.returncode == 0, cli_run.stderr
    assert filecmp.cmp(tmp_path / "plants.csv", tmp_path / "c" / "plants.csv", shallow=False)


def test_light_equals_the_command_line(cli_stand, tmp_path):
    # canopy light on the folder (a copy: light.json is written beside the stand) against
    # Stand.read(...).light and canopy.light on the same folder: the same rays, the same figures.
    import shutil

    folder = tmp_path / "stand"
    shutil.copytree(cli_stand, folder)
    r = cli("light", str(folder), "--sun", "55,200", "--sky-directions", "12", "--error", "0.004")
    assert r.returncode == 0, r.stderr
    want = json.load(open(folder / "light.json"))
    got = canopy.Stand.read(folder).light(suns=[(55, 200)], sky_directions=12, error=0.004)
    for key in ["tile", "lai", "ground_cover", "ground_cover_standard_error", "star", "direct", "leaf_angles"]:
        assert got[key] == want[key], key
    assert got["diffuse"]["intercepted_fraction"] == want["diffuse"]["intercepted_fraction"]
    csv = np.genfromtxt(folder / "light.csv", delimiter=",", names=True)
    assert np.array_equal(got["per_plant"]["sun1_fraction"], csv["sun1_fraction"])
    assert np.isclose(got["per_plant"]["sun1_share"].sum(), 1.0)
    again = canopy.light(folder, suns=[(55, 200)], sky_directions=12, error=0.004)
    assert again["direct"] == want["direct"]
    # A grown stand knows its rows: the same tile as the folder's report says.
    grown = canopy.Stand.grow(TOMATO, **ROWS).light(sky_directions=0)
    assert grown["tile"] == want["tile"]
    with pytest.raises(ValueError, match="--sun"):
        canopy.Stand.read(folder).light(suns=[(-5, 10)])
    with pytest.raises(ValueError, match="unknown option"):
        canopy.Stand.read(folder).light(sunz=[(5, 10)])


def test_light_of_a_stand_without_leaflets_is_undefined_not_zero(tmp_path):
    # STAR and leaf angles of no leaflet area: None in the results, NaN per plant (light.csv's
    # empty cells once stopped Stand.light with a parse error).
    bare = tmp_path / "bare.yaml"
    bare.write_text("name: t\naxiom: I(0.3,0.01)\norgans:\n  I: {prototype: cylinder, kind: internode}\n")
    got = canopy.Stand.grow(bare, rows=2, per_row=2, threads=1).light(suns=[(60, 180)], sky_directions=8, error=0.05)
    assert got["star"] is None and got["leaf_angles"]["mean_inclination_deg"] is None
    assert np.isnan(got["per_plant"]["star"]).all()
    assert (got["per_plant"]["sun1_fraction"] >= 0).all()


def test_an_export_replaces_the_stand_and_keeps_the_rest(tmp_path):
    out = tmp_path / "out"
    canopy.stand(TOMATO, out, rows=1, per_row=2, steps=10, backend="cpu")
    (out / "notes.txt").write_text("mine")
    (out / "renders").mkdir()
    (out / "renders" / "a.png").write_text("picture")
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=3, steps=10)
    s.export(out, formats=["obj"])
    # The earlier stand goes as a set: its report and contacts described it, not this one.
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt", "organs.csv", "plants.csv", "renders", "stand.mtl", "stand.obj"]
    assert (out / "notes.txt").read_text() == "mine" and (out / "renders" / "a.png").read_text() == "picture"
    assert sum(1 for _ in open(out / "plants.csv")) == 4
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # nothing left beside it


def test_a_failed_run_leaves_the_file_system_as_it_was(tmp_path):
    neg = tmp_path / "neg.yaml"
    neg.write_text("axiom: I(1, 0.1)\nsteps: 1\nproductions:\n  - I(a, b) -> I(a - 2, b)\norgans:\n"
                   "  I: {prototype: cylinder, kind: internode}\n")
    with pytest.raises((RuntimeError, ValueError)):  # an organ of negative length, found while growing
        canopy.stand(str(neg), tmp_path / "made" / "out")
    with pytest.raises(ValueError, match="plants may stand at most 1e\\+08 m from the origin"):
        canopy.stand(TOMATO, tmp_path / "far", rows=1, per_row=2, steps=8, plant_spacing=1e300)
    with pytest.raises(ValueError, match="farther from the origin than the 1e\\+08 m plants may stand"):
        canopy.Stand.grow(TOMATO, positions=np.array([[1e57, 0, 0, 1]]), steps=5)
    assert [p.name for p in tmp_path.iterdir()] == ["neg.yaml"]


def test_sweep_counts_failed_runs_kept_from_an_earlier_call(tmp_path):
    """A run past the module cap is recorded as failed; resuming keeps it and counts it."""
    kw = dict(plant_spacing=[0.3], steps=[10, 40], seeds=1, rows=1, per_row=2, backend="cpu", max_modules=500)
    first = canopy.sweep(TOMATO, tmp_path / "f", **kw)
    assert first["ran"] == 2 and first["failed"] == 1 and first["failed_in_table"] == 1
    again = canopy.sweep(TOMATO, tmp_path / "f", **kw)
    assert again["ran"] == 0 and again["failed"] == 0 and again["failed_in_table"] == 1
