"""What every paper-figure script shares: the command line, the one style (gdsmc.mplstyle, applied on
import), where the runs are, how to pick a case's file (paper tier, else quick tier, or the user's own
run), how to read an observable, how to run `granular-theory` on the input stored in an output file,
the residual panels, the mark of a panel without DSMC data, and how to save a figure (PDF and PNG,
after checking its text for internal words).

Every figure is a function registered with @figure("stem", ...); `main()` runs the figures of one
script, `make_all.py` those of every script, and both report which figures could not be made because
their runs are missing, with the ctest command that runs them.

Command line of every script (`--help` says more): [BUILD_DIR] [OUT_DIR] [--data PATH] [--run CASE=FILE]
[--out DIR]; runs from BUILD_DIR/validation-output/ (or --data, --run), figures to BUILD_DIR/figures/
(./figures/ with --data or --run).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# ---------------------------------------------------------------------------------------------------
# The command line. Defined before matplotlib is imported: --help must answer without writing anything,
# and importing matplotlib creates ~/.config/matplotlib (pyplot also a font cache).
# ---------------------------------------------------------------------------------------------------

RUNS_HELP = r"""runs:
  By default a figure draws the validation runs of the build tree: BUILD_DIR/validation-output/CASE.h5
  (the paper tier of a validation case) or else CASE_quick.h5 (its quick tier), as written by
  `ctest --test-dir BUILD_DIR -L quick -R '^validation\.'` (or -L paper). The cases each figure draws
  are listed above.
  Your own runs replace that directory with --data and --run: a file named CASE.h5 (or CASE_quick.h5),
  or a directory of such files, is drawn as that case; a file of any other name is mapped to its case
  with --run CASE=FILE, e.g. --run haff_cooling_alpha0.9=my-haff.h5 (made e.g. by `granular-dsmc
  validation/haff_cooling/haff.nml --output my-haff.h5`). Draw a run as the case whose input it
  shares: other sizes, seeds or times are fine, other physical parameters where the figure reads them
  from the file (seed000 the restitution); the theory is computed for the input stored in the file (by
  BUILD_DIR/bin/granular-theory), but titles and some labels name the case's parameters.

output:
  OUT_DIR/<figure>.pdf and .png (fixed names). A panel drawn without DSMC data says so in the panel
  ("theory only: no DSMC data") and on stderr. The list at the end says which figures were made,
  partial (drawn without some of their runs) or NOT MADE, and how to get the missing runs.

exit status:
  0 also when runs are missing; 1 when a figure fails on the data it has, or when a run given with
  --data or --run is drawn in no figure; 2 on a wrong command line.
"""


def _case_file(text):
    """CASE=FILE of --run: the case name without _quick (the given file wins over both tiers)."""
    case, sep, path = text.partition("=")
    if not sep or not case or not path:
        raise argparse.ArgumentTypeError(f"{text!r} is not CASE=FILE (e.g. haff_cooling_alpha0.9=my-haff.h5)")
    if not os.path.isfile(path):
        raise argparse.ArgumentTypeError(f"{path}: no such file")
    return case[:-6] if case.endswith("_quick") else case, os.path.abspath(path)


def _data_path(text):
    if not os.path.exists(text):
        raise argparse.ArgumentTypeError(f"{text}: no such file or directory")
    return os.path.abspath(text)


def command_line(script):
    """The parser of a script's command line: its docstring (the figures and the cases they draw), the
    options every script has, and those of `script.add_arguments(parser)` if it defines one."""
    p = argparse.ArgumentParser(prog=os.path.basename(script.__file__), description=script.__doc__,
                                epilog=RUNS_HELP, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build", nargs="?", metavar="BUILD_DIR",
                   help="build tree: its bin/granular-theory computes the theory and its validation-output/ "
                        "holds the runs (default: build/ of the source tree)")
    p.add_argument("out", nargs="?", metavar="OUT_DIR",
                   help="where the figures go (default: BUILD_DIR/figures, where `cmake --build BUILD_DIR "
                        "--target figures` writes them; with --data or --run: ./figures)")
    p.add_argument("--out", dest="out_option", metavar="DIR", help="the same as OUT_DIR")
    p.add_argument("--data", action="append", default=[], type=_data_path, metavar="PATH",
                   help="a run's output named CASE.h5 or CASE_quick.h5, or a directory of such files, "
                        "instead of BUILD_DIR/validation-output (repeatable; a later one wins)")
    p.add_argument("--run", action="append", default=[], type=_case_file, metavar="CASE=FILE",
                   help="draw FILE (any name) as the validation case CASE (repeatable; wins over --data)")
    if hasattr(script, "add_arguments"):
        script.add_arguments(p)
    return p


def parse_command_line(script):
    """The parsed command line of `script` (options and BUILD_DIR, OUT_DIR in any order)."""
    p = command_line(script)
    args = p.parse_intermixed_args()
    if args.out and args.out_option:
        p.error("OUT_DIR and --out both given")
    args.out = args.out or args.out_option
    return args


def _answer_help_first():
    """A figure script or make_all.py run with -h/--help: print its usage and exit 0 before anything
    is imported that writes files."""
    script = sys.modules.get("__main__")
    path = getattr(script, "__file__", None)
    if path and os.path.dirname(os.path.abspath(path)) == HERE and {"-h", "--help"} & set(sys.argv[1:]):
        command_line(script).parse_args()  # exits


_answer_help_first()

import glob  # noqa: E402
import json  # noqa: E402
import re  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402
import traceback  # noqa: E402

import h5py  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.figure  # noqa: E402
import matplotlib.text  # noqa: E402
import numpy as np  # noqa: E402

STYLE = os.path.join(HERE, "gdsmc.mplstyle")
plt.style.use(STYLE)

COLUMN = 3.4  # inches: one journal column
PAGE = 7.0    # inches: the full page width

# Where the runs are and where the figures go; configure() sets them (main() from the command line).
BUILD = os.path.join(ROOT, "build")
OUT = os.path.join(BUILD, "figures")
RUNS = os.path.join(BUILD, "validation-output")
THEORY = os.path.join(BUILD, "bin", "granular-theory")
FILES = {}           # file stem (CASE or CASE_quick) -> path: the runs found in RUNS or in --data
GIVEN = {}           # case -> path: the runs of --run
USER_DATA = []       # the --data paths and --run files (they replace RUNS; each must be drawn somewhere)
DOCS_DIR = None      # when set: the figures named in DOCS_STEMS are also written there as small PNGs
DOCS_STEMS = ()
DOCS_DPI = 150


def h5_files(path):
    """{file stem: path} of a run file or of the .h5 files in a directory."""
    paths = sorted(glob.glob(os.path.join(path, "*.h5"))) if os.path.isdir(path) else [path]
    return {os.path.basename(p)[:-3] if p.endswith(".h5") else os.path.basename(p): p for p in paths}


def configure(build=None, out=None, docs_dir=None, docs_stems=(), data=(), runs=()):
    """Sets the build tree, the output directory and the runs: BUILD/validation-output, or the files of
    `data` (paths) and `runs` ((case, path) pairs) instead."""
    global BUILD, OUT, RUNS, THEORY, FILES, GIVEN, USER_DATA, DOCS_DIR, DOCS_STEMS
    if build:
        BUILD = os.path.abspath(build)
    RUNS = os.path.join(BUILD, "validation-output")
    THEORY = os.path.join(BUILD, "bin", "granular-theory")
    USER_DATA = list(data) + [p for _, p in runs]
    GIVEN = dict(runs)
    FILES = {}
    for path in data if USER_DATA else [RUNS]:
        FILES.update(h5_files(path) if os.path.exists(path) else {})
    # a user's figures go to the working directory, the build tree's validation figures to the build tree
    default_out = os.path.join(os.getcwd(), "figures") if USER_DATA else os.path.join(BUILD, "figures")
    OUT = os.path.abspath(out) if out else default_out
    DOCS_DIR = os.path.abspath(docs_dir) if docs_dir else None
    DOCS_STEMS = tuple(docs_stems)


def configure_from(args, **docs):
    """configure() from a parsed command line (parse_command_line)."""
    configure(args.build, args.out, data=args.data, runs=args.run, **docs)


def runs_dir():
    """Where the runs come from, for messages."""
    return ", ".join(shown(p) for p in USER_DATA) if USER_DATA else shown(RUNS)


class Missing(Exception):
    """An input of a figure does not exist: a validation output (`case`, the name without _quick) or
    the granular-theory program (`case` None, `hint` says how to build it)."""

    def __init__(self, message, case=None, hint=None):
        super().__init__(message)
        self.case = case
        self.hint = hint


class TheoryError(RuntimeError):
    pass


# What the figure now running has read, the cases it asked for and those it looked for in vain
# (reported by run_figures).
_current = {}


def _reset_current():
    _current.clear()
    _current.update(used=[], asked=[], missing=[], written=[], no_dsmc=[])


_reset_current()


def _resolve(name):
    """The file of case `name`: given with --run, else CASE.h5 (paper tier), else CASE_quick.h5."""
    return GIVEN.get(name) or FILES.get(name) or FILES.get(name + "_quick")


def pick(name):
    """The run of validation case `name` (of BUILD/validation-output, or of --data and --run), noted as
    drawn; Missing if there is none."""
    _note(_current["asked"], name)
    path = _resolve(name)
    if path:
        note_used(path)
        return path
    note_missing(name)
    raise Missing(f"no run of {name} in {runs_dir()}", case=name)


def pick_or_none(name):
    """pick(name), or None when the case has no run (noted as missing all the same)."""
    try:
        return pick(name)
    except Missing:
        return None


def pick_some(names):
    """[(name, path)] of the cases of `names` that have a run (the others are noted as missing, and the
    figure is partial); Missing when none has."""
    found = []
    for name in names:
        try:
            found.append((name, pick(name)))
        except Missing:
            pass
    if not found:
        raise Missing(f"no run of {', '.join(names)} in {runs_dir()}", case=names[0])
    return found


def cases_starting(prefix):
    """[(case, path)] of every run whose case name starts with `prefix`, one per case as pick() takes
    it, sorted by case; not noted as drawn (the caller calls note_used for those it draws)."""
    cases = sorted({n[:-6] if n.endswith("_quick") else n for n in FILES} | set(GIVEN))
    found = [c for c in cases if c.startswith(prefix)]
    for c in found:
        _note(_current["asked"], c)
    return [(c, _resolve(c)) for c in found]


def _note(seen, item):
    if item not in seen:
        seen.append(item)


def note_used(path):
    _note(_current["used"], path)


def note_missing(name):
    """A validation case the figure would show but draws without (it shows the theory alone)."""
    _note(_current["missing"], name)


def origin(path):
    """Where a run comes from, for the report: its tier in the build tree, else its file name."""
    if USER_DATA:
        return shown(path)
    return "quick tier runs" if path.endswith("_quick.h5") else "paper tier runs"


def observable(group, name):
    """(time, value, error or None) of /observables/NAME under `group` (a file or a sweep point)."""
    g = group["observables"][name]
    err = g["error"][()] if "error" in g else None
    return g["time"][()], g["value"][()], err


def reduced_distribution(path):
    """Species 1's reduced distributions of a run (observables/reduced_distribution, docs/output.md):
    Phi_1, Delta_1, G_1 with their errors on the bin centres v, and lambda_1, c_1, beta_1, zeta*, alpha, N."""
    with h5py.File(path) as f:
        g = f["observables/reduced_distribution"]
        s = g["species_1"]
        edges = g["bin_edges"][()]
        d = {k: s[k][()] for k in ("value", "error", "delta", "delta_error", "g", "g_error")}
        d.update(v=0.5 * (edges[1:] + edges[:-1]), lam=s.attrs["lambda"], c=s.attrs["sonine_c"],
                 beta=s.attrs["tail_beta"], zeta=g.attrs["cooling_rate_reduced"],
                 alpha=float(np.ravel(f["parameters/system"].attrs["restitution"])[0]),
                 n=f["parameters/dsmc"].attrs["n_particles"])
    return d


def stored_input(path):
    """Namelist text and overrides stored in an output file's /parameters: those of &output only where
    they change the theory (the MSD's start, output:msd_*), not the file or the sampling."""
    with h5py.File(path) as f:
        p = f["parameters"].attrs
        text = p["namelist"]
        overrides = [o for o in p["overrides"].split("\n")
                     if o and (not o.startswith("output:") or o.startswith("output:msd_"))]
    return text, overrides


def run_theory(text, overrides=()):
    """granular-theory on a namelist text (in a temporary directory) with --set overrides."""
    if not os.path.exists(THEORY):
        raise Missing(f"{THEORY} does not exist", hint=f"cmake --build {shown(BUILD)} --target granular-theory, "
                      "or give the build tree that has it as BUILD_DIR")
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


def power_of_ten(x):
    """x for a title in TeX: 10^{n} when x is a power of ten (1e9 -> 10^{9}), else its 3 significant digits."""
    n = round(np.log10(x)) if x > 0 else 0
    return f"10^{{{n}}}" if x > 0 and abs(x / 10.0**n - 1.0) < 1e-9 else f"{x:.3g}"


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
        if not s or t.get_gid() == NO_DSMC_GID:
            continue
        outside = re.sub(r"(?<!\\)\$.*?(?<!\\)\$", " ", s)
        m = INTERNAL.search(outside)
        if m:
            bad.append((s, m.group(0)))
    return bad


# The mark of a panel without DSMC data names the missing runs: exempt from the internal-words check,
# since such a figure is a draft to be completed, not one to print.
NO_DSMC_GID = "gdsmc-no-dsmc"


def no_dsmc(ax, cases, theory_drawn=True):
    """Marks the panel `ax` as drawn without DSMC data (the runs of `cases`, a name or a list, are
    missing): a boxed note in the panel; save() says it on stderr and the report lists the figure."""
    cases = [cases] if isinstance(cases, str) else list(cases)
    for c in cases:
        note_missing(c)
    _mark(ax, "theory only: no DSMC data" if theory_drawn else "no DSMC data", cases)


def _mark(target, what, cases):
    """The note of no_dsmc() in a panel (axes coordinates) or across a whole figure: `what`, then the
    missing runs one a line (the first three)."""
    whole = isinstance(target, matplotlib.figure.Figure)
    names = "\n".join(cases[:3]) + ("\n..." if len(cases) > 3 else "")
    target.text(0.5, 0.5, f"{what}\nno run of\n{names}", ha="center", va="center", color="firebrick",
                fontsize="small", zorder=10, gid=NO_DSMC_GID,
                bbox=dict(boxstyle="round", fc="white", ec="firebrick", alpha=0.9),
                **({} if whole else {"transform": target.transAxes}))
    fig = target if whole else target.figure
    fig._gdsmc_no_dsmc = getattr(fig, "_gdsmc_no_dsmc", []) + [cases]


def _check_dsmc_drawn(fig, stem):
    """Says on stderr that `fig` has panels without DSMC data. A figure that read no run at all and is
    not marked is marked as a whole: no theory-only figure goes out without a word."""
    if not _current["used"] and not hasattr(fig, "_gdsmc_no_dsmc"):
        _mark(fig, "theory only: no DSMC data", _current["missing"] or ["its cases"])
    marks = getattr(fig, "_gdsmc_no_dsmc", [])
    if marks:
        names = ", ".join(sorted({c for cases in marks for c in cases}))
        print(f"warning: {stem}: {len(marks)} panel(s) drawn without DSMC data (no run of {names}); "
              "the figure says so", file=sys.stderr)
        _note(_current["no_dsmc"], stem)


def save(fig, stem):
    """Writes OUT/stem.pdf and OUT/stem.png (and, for the docs, DOCS_DIR/stem.png at DOCS_DPI). Refuses
    a figure whose texts hold internal words."""
    stem = stem[:-4] if stem.endswith(".png") else stem
    bad = internal_words(fig)
    if bad:
        plt.close(fig)
        raise ValueError(f"{stem}: internal words in the figure: "
                         + "; ".join(f"{w!r} in {s!r}" for s, w in bad))
    _check_dsmc_drawn(fig, stem)
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
    _current["written"].extend(written)
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
        _reset_current()
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


def _how_to_get(build, cases, partial=False):
    """How to get the runs of `cases`: the ctest command that makes them; with the user's runs first
    the --run option that gives them."""
    cmd = ctest_command(build, cases)
    if USER_DATA:
        return (f"{'to add them' if partial else 'give them'}: --run {cases[0]}=FILE.h5 ..., or make them: "
                f"{cmd}{_tier_note(cmd)}")
    return f"{'to add them' if partial else 'run them'}{_tier_note(cmd)}: {cmd}"


def _report_line(fig, status, d, build):
    """The lines of the report on one figure function."""
    stems = ", ".join(fig.stems)
    if status == "made":
        origins = sorted({origin(p) for p in d["used"]})
        return f"  made     {stems} ({', '.join(origins) or 'theory only'})"
    if status == "partial":
        line = (f"  partial  {stems}: drawn without {', '.join(d['missing'])}\n"
                f"           {_how_to_get(build, d['missing'], partial=True)}")
        if d["no_dsmc"]:
            line += f"\n           panels without DSMC data (the figure says so) in: {', '.join(d['no_dsmc'])}"
        return line
    if status == "missing" and d.get("hint"):
        return f"  NOT MADE {stems}: {d['message']}\n           build it: {d['hint']}"
    if status == "missing":
        return (f"  NOT MADE {stems}: runs missing: {', '.join(d['missing'])}\n"
                f"           {_how_to_get(build, d['missing'])}")
    return f"  ERROR    {stems} ({fig.name}):\n" + "\n".join("           " + ln
                                                            for ln in d["message"].rstrip().splitlines())


def report(results, build):
    """Prints what was made and what not (with the commands to make it); returns the number of errors."""
    counts = {}
    for fig, status, d in results:
        counts[status] = counts.get(status, 0) + 1
    print()
    print("figures:", ", ".join(f"{n} {s}" for s, n in sorted(counts.items())))
    if not FILES and not GIVEN:
        if USER_DATA:
            print(f"  no .h5 runs in {runs_dir()}")
        elif not os.path.isdir(build):
            print(f"  no build tree {shown(build)}: give yours as BUILD_DIR (see --help)")
        else:
            print(f"  no validation outputs in {shown(RUNS)}: run ctest --test-dir {shown(build)} -L quick -R "
                  "'^validation\\.' (reduced sizes) or -L paper (full sizes) first")
    for fig, status, d in results:
        print(_report_line(fig, status, d, build))
    return counts.get("error", 0)


def undrawn_user_data(results):
    """Says on stderr which --data and --run paths no figure drew a run from (a name that is no case
    of these figures, or a figure that lacks its other runs); returns their number."""
    used = [p for _, _, d in results for p in d["used"]]
    asked = sorted({c for _, _, d in results for c in d["asked"]})
    runs = {p: c for c, p in GIVEN.items()}
    undrawn = [p for p in USER_DATA if not any(u == p or u.startswith(p + os.sep) for u in used)]
    for p in undrawn:
        if p in runs:
            print(f"warning: {shown(p)} (--run {runs[p]}={shown(p)}) is in no figure: no figure here draws "
                  f"{runs[p]}, or the figure lacks other runs (see above)", file=sys.stderr)
            continue
        stem = os.path.basename(p)[:-3] if p.endswith(".h5") else os.path.basename(p)
        like = [c for c in asked if c.startswith(stem) or stem.startswith(c)] or asked
        cases = ", ".join(like[:12]) + (", ..." if len(like) > 12 else "")
        what, target = (shown(p), shown(p)) if os.path.isfile(p) else (f"no file of {shown(p)}", "FILE.h5")
        print(f"warning: {what} is in no figure: --data files are drawn by their name (CASE.h5 or "
              f"CASE_quick.h5); give it with --run CASE={target}, CASE one of the cases these figures asked "
              f"for: {cases}", file=sys.stderr)
    return len(undrawn)


def finish(results):
    """Reports the figures and the user's runs drawn in none; returns the exit status (see --help)."""
    errors = report(results, BUILD)
    return 1 if undrawn_user_data(results) or errors else 0


def main():
    """The command line of a figure script (--help): runs the figures that script registered and exits
    with finish()'s status."""
    configure_from(parse_command_line(sys.modules["__main__"]))
    mine = [f for f in REGISTRY if f.module == "__main__"]
    print(f"figures from {runs_dir()} into {shown(OUT)}")
    sys.exit(finish(run_figures(mine)))
