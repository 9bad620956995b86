"""canopy: penetration-free plant stands from parametric L-system grammars.

The same operations as the ``canopy`` command line, on the same C++ library:

>>> import canopy
>>> canopy.derive("grammars/classic/algae.yaml", steps=4)
'ABAABABA'
>>> stand = canopy.Stand.grow("grammars/tomato.yaml", rows=1, per_row=5, steps=14)
>>> stand.transforms.shape            # (organs, 4, 3) float32, a view of the stand's memory
>>> found = stand.detect(level="exact")
>>> report = stand.resolve(progress=lambda round, left, seconds: print(round, left))
>>> stand.export("out", formats=["glb"])
>>> canopy.stand("grammars/tomato.yaml", "out2", rows=2, per_row=5)   # canopy stand, returns report.json
>>> canopy.sweep("grammars/tomato.yaml", "sweep", density=[2, 3], steps=[16, 22], seeds=2)
>>> lit = stand.light(suns=[(60, 180)])                # canopy light: light.json as a dict, per_plant arrays
>>> canopy.light("out2", suns=[(60, 180)])             # on a folder (or a grammar with out=DIR)

Errors arrive as ValueError (bad grammar, option or list, with the command line's located
message ``FILE:LINE:COL: ...``) or FileNotFoundError (a grammar or positions file that cannot be
opened). Long calls release the GIL; a progress callback that raises stops the run and its
exception propagates.
"""
from ._canopy import ModuleCapError, Stand, __version__
from ._canopy import derive as _derive
from ._canopy import light as _light
from ._canopy import stand as _stand
from ._canopy import sweep as _sweep

__all__ = ["Stand", "derive", "stand", "light", "sweep", "sweep_rows", "ModuleCapError", "KINDS", "__version__"]

#: Organ kinds in the order of the ``kind`` codes of ``Stand.organs``.
KINDS = ("internode", "petiole", "rachis", "leaflet", "peduncle", "fruit", "flower")


def _path(p):
    """A path as the C++ side takes it: str, bytes (a name need not be UTF-8) or os.PathLike;
    anything else is refused with TypeError (str() made b'x' of bytes and a path of any object)."""
    import os

    return os.fspath(p)


def derive(grammar, *, steps=None, seed=None, stats=False, interpreted=False, max_modules=40_000_000, set=None,
           **constants):
    """The string a grammar derives (``canopy derive``), or with ``stats=True`` its module counts
    as a dict. Constants are overridden as keyword arguments (``derive(g, phyllotaxis=100)``, like
    ``--set phyllotaxis=100``) or as ``set={"phyllotaxis": 100}``."""
    overrides = dict(set or {})
    for name in constants:
        if name in overrides:  # as the command line refuses --set NAME=... given twice
            raise ValueError(f"--set {name}: given twice ({overrides[name]!r} in set= and {constants[name]!r} as "
                             f"{name}=); give it once")
    overrides.update(constants)
    return _derive(grammar, steps=steps, seed=seed, set=overrides, stats=stats, interpreted=interpreted,
                   max_modules=max_modules)


def stand(grammar, out, progress=None, **options):
    """``canopy stand GRAMMAR -o OUT`` with the command line's options, read by its own parser
    (``per_row=5`` for ``--per-row 5``, ``set={"name": value}`` for ``--set``, ``no_resolve=True``,
    ``random_rotation=False`` for ``--no-random-rotation``...). Writes the
    files and returns report.json as a dict. ``progress(round, contacts_left, seconds)`` is called
    each resolution round."""
    return _stand(_path(grammar), _path(out), options, progress)


def light(source, **options):
    """``canopy light SOURCE``: light interception of a stand folder (or of a grammar grown with
    canopy stand's options, ``out=DIR``). ``suns=[(elevation, azimuth), ...]``, ``latitude=``,
    ``day=``, ``hours=[...]``, ``sky="soc"``, ``sky_directions=46``, ``tile=(xmin, ymin, xmax,
    ymax)``, ``periodic=True``, ``error=0.002``, ``plant_error=``, ``rays_per_m2=``. Writes
    light.json and light.csv into the folder and returns light.json as a dict."""
    return _light(_path(source), options)


def sweep(grammar, out, progress=None, **options):
    """``canopy sweep GRAMMAR -o OUT``: lists as Python lists (``density=[2, 3]``) or strings
    (``steps="16:22:3"``). ``progress(index, total, row)`` is called after each run (its row
    already in OUT/runs.csv); raising from it stops the sweep, which resumes where it stopped
    when called again. Returns the counts; the rows are read by :func:`sweep_rows`."""
    return _sweep(_path(grammar), _path(out), options, progress)


def sweep_rows(out, summary=False):
    """The rows of OUT/runs.csv (or OUT/summary.csv) as a list of dicts, numbers as floats and
    every empty number as nan (a metric a run did not measure: STAR of a stand without leaflets,
    turns and resolved light without resolution, a failed run's; a standard deviation of one
    value). ``status``, ``backend`` and ``message`` stay text."""
    import csv
    import os

    text = {"status", "backend", "message"}
    rows = []
    out = _path(out)
    name = b"summary.csv" if summary else b"runs.csv"
    with open(os.path.join(out, name if isinstance(out, bytes) else name.decode()), newline="") as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                if k in text:
                    continue
                if v == "":
                    r[k] = float("nan")
                    continue
                try:
                    r[k] = float(v)
                except (TypeError, ValueError):
                    pass
            rows.append(r)
    return rows
