"""What every paper-figure script shares: the one style (gdsmc.mplstyle, applied on import), where the
validation outputs are, how to pick a case's file (paper tier, else quick tier), how to read an
observable, how to run `granular-theory` on the input stored in an output file, the residual panels,
and how to save a figure (PDF and PNG, after checking its text for internal words).

Every figure is a function registered with @figure("stem", ...); `main()` runs the figures of one
script, `make_all.py` those of every script, and both report which figures could not be made because
their validation runs are missing, with the ctest command that runs them.

Command line of every script: [BUILD_DIR] [OUT_DIR] (defaults: build/, paper-figures/out/).
"""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import traceback

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.text  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
STYLE = os.path.join(HERE, "gdsmc.mplstyle")
plt.style.use(STYLE)

COLUMN = 3.4  # inches: one journal column
PAGE = 7.0    # inches: the full page width

# Where the runs are and where the figures go; configure() sets them (main() from the command line).
BUILD = os.path.join(ROOT, "build")
OUT = os.path.join(ROOT, "paper-figures", "out")
RUNS = os.path.join(BUILD, "validation-output")
THEORY = os.path.join(BUILD, "bin", "granular-theory")
DOCS_DIR = None      # when set: the figures named in DOCS_STEMS are also written there as small PNGs
DOCS_STEMS = ()
DOCS_DPI = 150


def configure(build=None, out=None, docs_dir=None, docs_stems=()):
    global BUILD, OUT, RUNS, THEORY, DOCS_DIR, DOCS_STEMS
    if build:
        BUILD = os.path.abspath(build)
    if out:
        OUT = os.path.abspath(out)
    RUNS = os.path.join(BUILD, "validation-output")
    THEORY = os.path.join(BUILD, "bin", "granular-theory")
    DOCS_DIR = os.path.abspath(docs_dir) if docs_dir else None
    DOCS_STEMS = tuple(docs_stems)


def runs_dir():
    return RUNS


class Missing(Exception):
    """An input of a figure does not exist: a validation output (`case`, the name without _quick) or
    the granular-theory program (`case` None, `hint` says how to build it)."""

    def __init__(self, message, case=None, hint=None):
        super().__init__(message)
        self.case = case
        self.hint = hint


class TheoryError(RuntimeError):
    pass


# What the figure now running has read and what it looked for in vain (reported by run_figures).
_current = {"used": [], "missing": []}


def pick(name):
    """The paper-tier file of a validation case, or its quick variant."""
    for candidate in (name, name + "_quick"):
        path = os.path.join(RUNS, candidate + ".h5")
        if os.path.exists(path):
            if path not in _current["used"]:
                _current["used"].append(path)
            return path
    if name not in _current["missing"]:
        _current["missing"].append(name)
    raise Missing(f"no output for {name} in {RUNS}", case=name)


def note_used(path):
    if path not in _current["used"]:
        _current["used"].append(path)


def note_missing(name):
    """A validation case the figure would show but draws without (it shows the theory alone)."""
    if name not in _current["missing"]:
        _current["missing"].append(name)


def tier(path):
    return "quick tier" if path.endswith("_quick.h5") else "paper tier"


def observable(group, name):
    """(time, value, error or None) of /observables/NAME under `group` (a file or a sweep point)."""
    g = group["observables"][name]
    err = g["error"][()] if "error" in g else None
    return g["time"][()], g["value"][()], err


def stored_input(path):
    """Namelist text and overrides (without output:) stored in an output file's /parameters."""
    with h5py.File(path) as f:
        p = f["parameters"].attrs
        text = p["namelist"]
        overrides = [o for o in p["overrides"].split("\n") if o and not o.startswith("output:")]
    return text, overrides


def run_theory(text, overrides=()):
    """granular-theory on a namelist text (in a temporary directory) with --set overrides."""
    if not os.path.exists(THEORY):
        raise Missing(f"{THEORY} does not exist", hint=f"cmake --build {BUILD} --target granular-theory")
    with tempfile.TemporaryDirectory(prefix="gdsmc-theory-") as tmp:
        nml = os.path.join(tmp, "theory.nml")
        with open(nml, "w") as out:
            out.write(text)
        cmd = [THEORY, nml]
        for o in overrides:
            cmd += ["--set", o]
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp)
        if r.returncode:
            raise TheoryError(f"granular-theory failed on\n{text}\n{r.stderr.strip()}")
        return json.loads(r.stdout)


def theory(path, extra=()):
    """granular-theory on the namelist and overrides stored in the output file (plus `extra`)."""
    text, overrides = stored_input(path)
    return run_theory(text, overrides + list(extra))


APPROXIMATION_NAMES = {"maxwellian": "Maxwellian", "first_sonine": "first Sonine", "exact": "exact",
                       "high_velocity_asymptotics": "high-velocity asymptotics"}


def approximation(th, key):
    """The legend name of the approximation granular-theory states for `key` ("Maxwellian", ...)."""
    name = th.get("approximations", {}).get(key)
    if name is None:
        raise KeyError(f"granular-theory states no approximation for {key}")
    return APPROXIMATION_NAMES.get(name, name.replace("_", " "))


def on_times(t, tt, yy):
    """Theory values yy (on the times tt) at the DSMC times t: yy itself when the times agree, else
    linear interpolation in ln t (per column)."""
    tt, yy = np.asarray(tt, float), np.asarray(yy, float)
    if tt.shape == np.shape(t) and np.allclose(tt, t, rtol=1e-9, atol=0):
        return yy
    x, xt = np.log(np.maximum(t, 1e-300)), np.log(np.maximum(tt, 1e-300))
    if yy.ndim == 1:
        return np.interp(x, xt, yy)
    return np.stack([np.interp(x, xt, yy[:, k]) for k in range(yy.shape[1])], axis=1)


# ---------------------------------------------------------------------------------------------------
# Main panels with residual panels below
# ---------------------------------------------------------------------------------------------------

SE_LABEL = "DSMC $-$ theory\n(standard errors)"
PERCENT_LABEL = "DSMC/theory $-$ 1\n(%)"


def with_residuals(ncols=1, width=COLUMN, height=3.4, ratio=(3.0, 1.2), sharex="col"):
    """A figure with `ncols` main panels over as many residual panels: (fig, main axes, residual axes)
    (arrays of length ncols, or single axes when ncols = 1)."""
    fig, axes = plt.subplots(2, ncols, figsize=(width, height), sharex=sharex, squeeze=False,
                             gridspec_kw=dict(height_ratios=ratio))
    fig._gdsmc_hspace = 0.06  # applied by save() after tight_layout: the residuals sit right below
    for ax in axes[0]:
        ax.tick_params(labelbottom=False)
    if ncols == 1:
        return fig, axes[0, 0], axes[1, 0]
    return fig, axes[0], axes[1]


def residuals(ar, x, y, dy, y_theory, kind="se", **style):
    """Draws DSMC minus theory on the residual axes `ar`: in standard errors (kind "se": (y - theory)/dy,
    points where dy > 0 only; grey band +-2) or in percent (kind "percent": 100 (y/theory - 1) with the
    error bars 100 dy/theory). Returns the plotted values."""
    x, y, y_theory = np.asarray(x, float), np.asarray(y, float), np.asarray(y_theory, float)
    dy = np.zeros_like(y) if dy is None else np.asarray(dy, float)
    style = {"fmt": "o", "ms": 3, **style}
    style.pop("label", None)
    if kind == "se":
        ok = dy > 0
        z = (y[ok] - y_theory[ok]) / dy[ok]
        style.pop("capsize", None)
        fmt = style.pop("fmt")
        ar.plot(x[ok], z, fmt, **{k: v for k, v in style.items() if k != "yerr"})
        if not getattr(ar, "_gdsmc_band", False):
            ar.axhspan(-2, 2, color="0.88", lw=0, zorder=0)
            ar._gdsmc_band = True
        ar.set_ylabel(SE_LABEL)
        values = z
    elif kind == "percent":
        p = 100.0 * (y / y_theory - 1.0)
        ar.errorbar(x, p, yerr=100.0 * dy / np.abs(y_theory), **style)
        ar.set_ylabel(PERCENT_LABEL)
        values = p
    else:
        raise ValueError(kind)
    ar.axhline(0.0, color="0.4", lw=0.7, zorder=1)
    return values


# ---------------------------------------------------------------------------------------------------
# Saving: PDF and PNG, text checked for internal words
# ---------------------------------------------------------------------------------------------------

# Words a reader of a journal figure cannot know: run tiers, file names, namelist variables, the
# project's internal citations. Checked outside mathtext ($...$) in every text of a figure.
INTERNAL = re.compile(r"\bquick\b|\btier\b|\.h5\b|\.nml\b|\bERRATA\b|\bseed\s*0\d\d\b|\bnamelist\b"
                      r"|\b[A-Za-z]+_[A-Za-z0-9_]+\b", re.I)


def internal_words(fig):
    """[(text, offending word)] of the texts of `fig` (labels, titles, legends, ticks, annotations)."""
    bad = []
    for t in fig.findobj(matplotlib.text.Text):
        s = t.get_text()
        if not s:
            continue
        outside = re.sub(r"(?<!\\)\$.*?(?<!\\)\$", " ", s)
        m = INTERNAL.search(outside)
        if m:
            bad.append((s, m.group(0)))
    return bad


def save(fig, stem):
    """Writes OUT/stem.pdf and OUT/stem.png (and, for the docs, DOCS_DIR/stem.png at DOCS_DPI). Refuses
    a figure whose texts hold internal words."""
    stem = stem[:-4] if stem.endswith(".png") else stem
    bad = internal_words(fig)
    if bad:
        plt.close(fig)
        raise ValueError(f"{stem}: internal words in the figure: "
                         + "; ".join(f"{w!r} in {s!r}" for s, w in bad))
    os.makedirs(OUT, exist_ok=True)
    fig.tight_layout(pad=0.3)
    if hasattr(fig, "_gdsmc_hspace"):
        fig.subplots_adjust(hspace=fig._gdsmc_hspace)
    inputs = ", ".join(os.path.basename(p) for p in _current["used"]) or "theory only"
    meta = {"Title": stem, "Subject": f"granular-dsmc validation runs: {inputs}"}
    written = []
    for ext in ("pdf", "png"):
        path = os.path.join(OUT, f"{stem}.{ext}")
        fig.savefig(path, metadata=meta if ext == "pdf" else {"Title": stem, "Description": meta["Subject"]})
        written.append(path)
    if DOCS_DIR and stem in DOCS_STEMS:
        os.makedirs(DOCS_DIR, exist_ok=True)
        path = os.path.join(DOCS_DIR, f"{stem}.png")
        fig.savefig(path, dpi=DOCS_DPI, metadata={"Title": stem, "Description": meta["Subject"]})
        written.append(path)
    plt.close(fig)
    _current.setdefault("written", []).extend(written)
    for path in written:
        print("wrote", shown(path))


# ---------------------------------------------------------------------------------------------------
# The registry of figures, and running them
# ---------------------------------------------------------------------------------------------------

class Figure:
    def __init__(self, fn, stems):
        self.fn, self.stems = fn, tuple(stems)
        self.module = fn.__module__
        self.name = f"{fn.__module__}.{fn.__name__}"


REGISTRY = []


def figure(*stems):
    """Registers the decorated function as drawing the figures `stems` (file names without extension)."""
    def register(fn):
        REGISTRY.append(Figure(fn, stems))
        return fn
    return register


def run_figures(figures):
    """Runs every figure; returns [(figure, status, detail)] with status 'made', 'partial' (made without
    some of its runs), 'missing' (not made: a run or granular-theory is missing) or 'error'."""
    results = []
    for fig in figures:
        _current.clear()
        _current.update(used=[], missing=[], written=[])
        try:
            fig.fn()
        except Missing as e:
            plt.close("all")
            results.append((fig, "missing", dict(_current, hint=e.hint, message=str(e))))
            continue
        except Exception:  # a real error: reported with its traceback
            plt.close("all")
            results.append((fig, "error", dict(_current, message=traceback.format_exc())))
            continue
        status = "partial" if _current["missing"] else "made"
        if not _current["written"]:
            status = "missing" if _current["missing"] else "error"
        results.append((fig, status, dict(_current, hint=None,
                                          message="" if _current["written"] else "wrote nothing")))
    return results


def shown(path):
    """`path` relative to the working directory when it lies below it, else absolute."""
    rel = os.path.relpath(path)
    return path if rel.startswith("..") else rel


def validation_tests(build):
    """Names of the validation tests ctest knows in `build` (from the generated CTestTestfile.cmake)."""
    path = os.path.join(build, "validation", "CTestTestfile.cmake")
    try:
        with open(path) as f:
            return set(re.findall(r"add_test\(\[=\[validation\.([^\]]+)\]=\]|add_test\(validation\.(\S+)", f.read()))
    except OSError:
        return set()


def ctest_command(build, cases):
    """The ctest command that runs the validation cases `cases` (quick variant where there is one)."""
    known = {a or b for a, b in validation_tests(build)}
    parts = []
    for c in cases:
        if c + "_quick" in known:
            parts.append(re.escape(c + "_quick"))
        elif c in known:
            parts.append(re.escape(c))
        else:  # the build tree's test list is not readable: either tier
            parts.append(re.escape(c) + "(_quick)?")
    return f"ctest --test-dir {shown(build)} -R '^validation\\.({'|'.join(parts)})$'"


def _tier_note(cmd):
    return "" if "_quick" in cmd else " (paper tier: these cases have no quick variant)"


def report(results, build):
    """Prints what was made and what not (with the commands to make it); returns the number of errors."""
    counts = {}
    for fig, status, d in results:
        counts[status] = counts.get(status, 0) + 1
    print()
    print("figures:", ", ".join(f"{n} {s}" for s, n in sorted(counts.items())))
    runs = os.path.join(build, "validation-output")
    if not glob.glob(os.path.join(runs, "*.h5")):
        print(f"  no validation outputs in {shown(runs)}: run ctest --test-dir {shown(build)} -L quick -R "
              "'^validation\\.' (reduced sizes) or -L paper (full sizes) first")
    for fig, status, d in results:
        stems = ", ".join(fig.stems)
        if status == "made":
            tiers = sorted({tier(p) for p in d["used"]})
            print(f"  made     {stems}" + (f" ({', '.join(tiers)} runs)" if tiers else " (theory only)"))
        elif status == "partial":
            cmd = ctest_command(build, d["missing"])
            print(f"  partial  {stems}: drawn without {', '.join(d['missing'])}\n"
                  f"           to add them{_tier_note(cmd)}: {cmd}")
        elif status == "missing":
            if d.get("hint"):
                print(f"  NOT MADE {stems}: {d['message']}\n           build it: {d['hint']}")
            else:
                cmd = ctest_command(build, d["missing"])
                print(f"  NOT MADE {stems}: validation runs missing: {', '.join(d['missing'])}\n"
                      f"           run them{_tier_note(cmd)}: {cmd}")
        else:
            print(f"  ERROR    {stems} ({fig.name}):\n" + "\n".join("           " + ln
                                                                   for ln in d["message"].rstrip().splitlines()))
    return counts.get("error", 0)


def main():
    """Command line of a figure script: [BUILD_DIR] [OUT_DIR]; runs the figures that script registered.
    Exit status 1 on real errors only (a missing validation run is reported, not an error)."""
    args = [a for a in sys.argv[1:] if not a.startswith("-")]
    configure(args[0] if args else None, args[1] if len(args) > 1 else None)
    mine = [f for f in REGISTRY if f.module == "__main__"]
    errors = report(run_figures(mine), BUILD)
    sys.exit(1 if errors else 0)
