"""Bad input through the Python module: the command line's bounds and messages as exceptions,
never a crash of the interpreter. Each case that crashed runs in a child interpreter, so a
regression fails this test instead of killing pytest. Run by ctest (suite `python`)."""
import os
import subprocess
import sys

import numpy as np
import pytest

import canopy

SRC = os.environ.get("CANOPY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
TOMATO = os.path.join(SRC, "grammars", "tomato.yaml")
ALGAE = os.path.join(SRC, "grammars", "classic", "algae.yaml")


def in_child(code):
    """Runs `code` in a fresh interpreter with this one's canopy; its exit status and output."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    return subprocess.run([sys.executable, "-c", "import canopy\n" + code], capture_output=True, text=True, env=env,
                          timeout=120)


def test_deep_expressions_raise_instead_of_killing_the_interpreter(tmp_path):
    deep = tmp_path / "deep.yaml"
    deep.write_text("axiom: A(" + "(" * 30000 + "1" + ")" * 30000 + ")\n")
    r = in_child(f"""
try:
    canopy.derive({str(deep)!r})
except ValueError as e:
    print('ValueError', e)
""")
    assert r.returncode == 0, r.stderr
    assert "deep.yaml:1:266: expression nested too deeply" in r.stdout


def test_thread_counts_past_the_maximum_raise():
    r = in_child(f"""
for call in (lambda: canopy.Stand.grow({TOMATO!r}, rows=1, per_row=2, steps=4, threads=100000),
             lambda: canopy.stand({TOMATO!r}, {os.devnull!r} + '-no', steps=4, threads=100000)):
    try:
        call()
    except ValueError as e:
        print('ValueError', e)
""")
    assert r.returncode == 0, r.stderr
    assert r.stdout.count("ValueError") == 2
    assert "100000" in r.stdout
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=4)
    with pytest.raises(ValueError, match="--threads: needs a whole number from 0 to 1024, got 100000"):
        s.detect(threads=100000)


def test_omp_num_threads_past_the_maximum_raises():
    env = dict(os.environ, OMP_NUM_THREADS="100000", PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    code = f"""import canopy
try:
    canopy.Stand.grow({TOMATO!r}, rows=1, per_row=2, steps=4)
except ValueError as e:
    print('ValueError', e)
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "ValueError OMP_NUM_THREADS asks for 100000 threads" in r.stdout


def test_steps_out_of_range_raise():
    for steps in (-3, 100001):
        with pytest.raises(ValueError, match=r"steps: needs a whole number from 0 to 100000"):
            canopy.derive(ALGAE, steps=steps)  # -3 returned the axiom
        with pytest.raises(ValueError, match=r"the derivation steps must lie in 0\.\.100000"):
            canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=steps)
    assert canopy.derive(ALGAE, steps=0) == "A"


def test_paths_as_bytes_and_path_like(tmp_path):
    assert canopy.derive(os.fsencode(ALGAE), steps=3) == canopy.derive(ALGAE, steps=3)  # was looked up as "b'...'"
    out = tmp_path / "out"
    report = canopy.stand(os.fsencode(TOMATO), os.fsencode(str(out)), rows=1, per_row=1, steps=4, backend="cpu")
    assert report["counts"]["plants"] == 1
    assert (out / "organs.csv").exists()
    assert not (tmp_path.parent / "b'").exists()
    with pytest.raises(TypeError):
        canopy.stand(3, str(tmp_path / "x"))


def test_array_views_are_read_only():
    s = canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=6)
    before = s.detect(backend="cpu")["counts"]
    for view in (s.transforms, s.base_points, s.organs):
        assert not view.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        s.transforms[0, 0, 0] = np.nan  # was used by detect() as it was
    with pytest.raises(ValueError, match="read-only"):
        s.organs["parent"][1] = 12345
    assert s.detect(backend="cpu")["counts"] == before
    copy = s.transforms.copy()
    copy[0, 0, 0] = 1  # a copy is the user's to change
    assert np.isfinite(s.transforms).all()


def test_row_options_are_named():
    with pytest.raises(ValueError, match=r"the jitter must be a finite number of metres, not negative \(got inf\)"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=2, steps=4, jitter=float("inf"))
    with pytest.raises(ValueError, match="the row spacing"):
        canopy.Stand.grow(TOMATO, rows=2, per_row=1, steps=4, row_spacing=float("nan"))


def test_level_of_detail_one_range(tmp_path):
    g = tmp_path / "lod.yaml"
    g.write_text("axiom: L(1, 0.5)\norgans:\n  L: {prototype: leaflet, kind: leaflet, lod: 17}\n")
    with pytest.raises(ValueError, match=r"lod.yaml:3:47: lod must be between 1 and 16, got 17"):
        canopy.Stand.grow(str(g))
    with pytest.raises(ValueError, match=r"the level of detail must lie in 1\.\.16 \(got 17\)"):
        canopy.Stand.grow(TOMATO, rows=1, per_row=1, steps=4, lod=17)


def test_positions_grammar_cells_stay_in_their_folder(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("the secret line\n")
    folder = tmp_path / "pos"
    folder.mkdir()
    positions = folder / "p.csv"
    positions.write_text("x,y,rotation,seed,grammar\n0,0,0,1,../secret.txt\n")
    with pytest.raises(ValueError, match="leaves the positions file's folder") as e:
        canopy.stand(TOMATO, str(tmp_path / "out"), positions=str(positions), steps=4, backend="cpu")
    with pytest.raises(ValueError) as e:
        canopy.stand(TOMATO, str(tmp_path / "out"), positions=str(positions), steps=4, backend="cpu", any_grammar_path=True)
    assert "a grammar file is a YAML map" in str(e.value)
    assert "secret line" not in str(e.value)


def test_organ_sizes_past_float_range_are_located(tmp_path):
    g = tmp_path / "huge.yaml"
    g.write_text("organs:\n  L: {prototype: leaflet, kind: leaflet}\naxiom: L(1e300, 1e300)\n")
    with pytest.raises(ValueError, match=r"huge.yaml:3:10: plant 0 \(seed 1\), module 0 .*more than the 1000000 m"):
        canopy.Stand.grow(str(g), positions=np.array([[0, 0, 0, 1]]))


def test_reading_a_stand_refuses_what_canopy_does_not_write(tmp_path):
    out = tmp_path / "s"
    canopy.stand(TOMATO, str(out), rows=1, per_row=2, steps=6, backend="cpu")
    lines = (out / "organs.csv").read_text().split("\n")
    cells = lines[1].split(",")
    cells[12] = "nan"
    lines[1] = ",".join(cells)
    (out / "organs.csv").write_text("\n".join(lines))
    with pytest.raises(RuntimeError, match=r"organs.csv:2: column 13 'nan' is not a finite number"):
        canopy.Stand.read(str(out))
    (out / "organs.csv").write_text("")
    with pytest.raises(RuntimeError, match="organs.csv:1: expected the header"):
        canopy.Stand.read(str(out))


def test_unknown_backend_and_caster_refused(tmp_path):
    # The command line checks --backend as it parses; the module's keywords reach the same check.
    with pytest.raises(ValueError, match="--backend: gpu not in {cpu,cuda,auto}"):
        canopy.stand(TOMATO, tmp_path / "s", rows=1, per_row=2, steps=4, backend="gpu")
    assert not (tmp_path / "s").exists()
    out = tmp_path / "l"
    canopy.stand(TOMATO, out, rows=1, per_row=2, steps=4, backend="cpu")
    with pytest.raises(ValueError, match="--backend: CUDA not in {cpu,cuda,auto}"):
        canopy.light(str(out), suns=[(60, 180)], backend="CUDA")
    with pytest.raises(ValueError, match="--caster: bogus not in {auto,trace,raster}"):
        canopy.light(str(out), suns=[(60, 180)], caster="bogus")


def test_two_threads_first_arrays_do_not_stall():
    # Two threads whose first calls return NumPy arrays, in an interpreter that has not imported
    # NumPy itself: pybind11's one-time NumPy set-up stalled both for good.
    young = os.path.join(SRC, "grammars", "tomato_young.yaml")
    r = in_child(f"""
import threading
stands = [canopy.Stand.grow({young!r}, rows=1, per_row=3, threads=1) for _ in range(2)]
ts = [threading.Thread(target=lambda s=s: s.detect(threads=1)) for s in stands]
[t.start() for t in ts]
[t.join(60) for t in ts]
print("stalled" if any(t.is_alive() for t in ts) else "done", flush=True)
import os
os._exit(0)
""")
    assert r.returncode == 0 and r.stdout.strip() == "done", r.stdout + r.stderr
