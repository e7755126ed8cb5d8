#!/usr/bin/python3
"""Regenerates every paper figure from the validation runs of a build tree (or from your own runs), and
checks the scripts.

Runs every figure of every script in paper-figures/ (each *.py but this file and figures_common.py; each
script's --help lists its figures and the validation cases they draw) and writes OUT_DIR/<figure>.pdf
and .png. `cmake --build BUILD_DIR --target figures` runs `make_all.py BUILD_DIR BUILD_DIR/figures`.
At the end it lists each figure: made (from which tier or file), partial (drawn without some of its
runs) or NOT MADE, with the ctest command that runs the missing validation cases.
"""
import ast
import datetime
import glob
import importlib
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SKIP = 77  # ctest SKIP_RETURN_CODE

# The figures docs/validation-summary.md shows (small PNGs in docs/figures/).
DOCS_STEMS = (
    "seed000_fig1_fig3_haff", "seed000_fig2_fig4_collisions", "seed000_fig5_velocity",
    "seed000_fig6_polydisperse", "seed003_fig1_gamma_time", "seed003_fig2_cumulants",
    "seed003_fig4_gamma_alpha_mu", "seed003_fig7_tail", "seed001_fig2_msd_binary",
    "seed004_fig6_viscosity", "agg_frag_full", "hcs_mixture_temperature_ratios",
)


def scripts():
    """The figure scripts: every *.py of paper-figures/ but the shared module and this file."""
    own = {"figures_common.py", os.path.basename(__file__)}
    return sorted(p for p in glob.glob(os.path.join(HERE, "*.py")) if os.path.basename(p) not in own)


def load_scripts():
    """Imports every figure script (their figures register in figures_common.REGISTRY)."""
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    return [importlib.import_module(os.path.basename(p)[:-3]) for p in scripts()]


def add_arguments(parser):
    """The options of make_all.py besides those of every figure script (figures_common.command_line)."""
    parser.add_argument("--docs", nargs="?", const=os.path.join(ROOT, "docs", "figures"), metavar="DIR",
                        help="also write the figures the docs show (DOCS_STEMS) as small PNGs to DIR "
                             "(default docs/figures/), with DIR/sources.txt: the runs each was drawn from")
    parser.add_argument("--check", action="store_true",
                        help="the smoke test of ctest figures.scripts (needs no runs; writes only to a "
                             "temporary directory): every script imports figures_common first and saves "
                             "only through it, overrides no style setting, lists the cases it draws in its "
                             "--help, and each figure runs up to its first missing input without any other "
                             "error; save() writes PDF and PNG, refuses internal words and marks a figure "
                             "without DSMC data. Exit status 77 (ctest: skipped) when matplotlib, numpy "
                             "or h5py cannot be imported")


def generate(args):
    import figures_common as fc
    fc.configure_from(args, docs_dir=args.docs, docs_stems=DOCS_STEMS if args.docs else ())
    load_scripts()
    print(f"figures from {fc.runs_dir()} into {fc.shown(fc.OUT)}"
          + (f" (docs PNGs: {fc.shown(fc.DOCS_DIR)})" if args.docs else ""))
    results = fc.run_figures(fc.REGISTRY)
    status = fc.finish(results)
    if args.docs:
        write_docs_sources(fc.DOCS_DIR, results)
    return status


def write_docs_sources(docs_dir, results):
    """DIR/sources.txt: the runs each docs figure was drawn from."""
    os.makedirs(docs_dir, exist_ok=True)
    with open(os.path.join(docs_dir, "sources.txt"), "w") as out:
        out.write("Written by `paper-figures/make_all.py --docs` on "
                  f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC from the validation "
                  "outputs below (build/validation-output/).\n\n")
        for fig, status, d in results:
            for stem in fig.stems:
                if stem in DOCS_STEMS and status in ("made", "partial"):
                    out.write(f"{stem}.png: {', '.join(os.path.basename(p) for p in d['used'])}\n")


# -------------------------------------------------------------------------------------------------
# --check: the smoke test
# -------------------------------------------------------------------------------------------------

FORBIDDEN_CALLS = {"savefig": "save through figures_common.save (PDF and PNG)",
                   "use": "the style is figures_common's (gdsmc.mplstyle)",
                   "rc": "no style overrides: gdsmc.mplstyle", "rcdefaults": "no style overrides",
                   "show": "scripts write files"}


def static_problems(path):
    """What in a script's source breaks the rules (returns a list of messages)."""
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    problems = []
    imports_common = False
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module == "figures_common":
            imports_common = True
        if isinstance(node, ast.Import) and any(a.name == "figures_common" for a in node.names):
            imports_common = True
        if isinstance(node, ast.Call):
            name = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", "")
            owner = node.func.value if isinstance(node.func, ast.Attribute) else None
            owner_name = getattr(owner, "attr", getattr(owner, "id", ""))
            if name == "use":  # matplotlib.use("Agg") is harmless; style.use is not
                if owner_name == "style":
                    problems.append(f"line {node.lineno}: style.use(): {FORBIDDEN_CALLS[name]}")
            elif name in FORBIDDEN_CALLS:
                problems.append(f"line {node.lineno}: {name}(): {FORBIDDEN_CALLS[name]}")
            if name == "update" and owner_name == "rcParams":
                problems.append(f"line {node.lineno}: rcParams.update(): no style overrides")
            for kw in node.keywords:
                if kw.arg in ("fontsize", "size", "title_fontsize") and isinstance(kw.value, ast.Constant) \
                        and isinstance(kw.value.value, (int, float)) and name != "figure":
                    problems.append(f"line {node.lineno}: {kw.arg}={kw.value.value}: font sizes come from the style")
        if isinstance(node, (ast.Assign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for t in targets:
                if isinstance(t, ast.Subscript) and getattr(t.value, "attr", getattr(t.value, "id", "")) == "rcParams":
                    problems.append(f"line {node.lineno}: rcParams[...] = ...: no style overrides")
    if not imports_common:
        problems.append("does not import figures_common (the style, save() for PDF and PNG)")
    problems += import_order_problems(tree)
    return problems


HEAVY = ("matplotlib", "h5py", "numpy")


def import_order_problems(tree):
    """figures_common must come before matplotlib, h5py, numpy: it answers --help before they load
    (importing matplotlib writes ~/.config/matplotlib and a font cache)."""
    for node in tree.body:
        names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
            [node.module or ""] if isinstance(node, ast.ImportFrom) else []
        if "figures_common" in names:
            return []
        heavy = [n for n in names if n.split(".")[0] in HEAVY]
        if heavy:
            return [f"line {node.lineno}: imports {heavy[0]} before figures_common (--help must not load it)"]
    return []


def documented_cases(doc):
    """The case names a script's docstring lists, brace patterns expanded: viscosity_alpha{1.0,0.9} is
    viscosity_alpha1.0 and viscosity_alpha0.9."""
    import re
    names = set()
    for token in re.findall(r"[\w.{},]+", doc or ""):
        todo = [token]
        while todo:
            t = todo.pop()
            m = re.search(r"\{([^{}]*)\}", t)
            if m:
                todo += [t[:m.start()] + alt + t[m.end():] for alt in m.group(1).split(",")]
            else:
                names.add(t.strip(".,"))
    return names


def check():
    failures = []
    paths = scripts()
    if not paths:
        failures.append("no figure scripts found")
    for p in paths:
        for msg in static_problems(p):
            failures.append(f"{os.path.basename(p)}: {msg}")

    import matplotlib
    import matplotlib.pyplot as plt
    import numpy as np
    import figures_common as fc
    style = matplotlib.rc_params_from_file(fc.STYLE, use_default_template=False)

    def style_drift():
        return sorted(k for k, v in style.items() if matplotlib.rcParams[k] != v)

    if style_drift():
        failures.append(f"figures_common does not apply gdsmc.mplstyle: {style_drift()}")

    with tempfile.TemporaryDirectory(prefix="gdsmc-figcheck-") as tmp:
        empty_build = os.path.join(tmp, "build")  # no validation outputs, no granular-theory
        out = os.path.join(tmp, "out")
        docs = os.path.join(tmp, "docs")
        os.makedirs(os.path.join(empty_build, "validation-output"))
        fc.configure(empty_build, out, docs, ("synthetic",))

        # save(): PDF and PNG, residual panels of both kinds, the docs copy
        fig, ax, ar = fc.with_residuals()
        x = np.linspace(1.0, 2.0, 5)
        ax.errorbar(x, x, yerr=0.1 + 0 * x, fmt="o", label="DSMC")
        ax.plot(x, x, "-", label=r"first Sonine, $\alpha = 0.5$")
        fc.residuals(ar, x, x + 0.01, 0.1 + 0 * x, x, kind="se")
        fc.residuals(ar, x, x + 0.01, 0.1 + 0 * x, x, kind="percent")
        ax.set(ylabel=r"$T/T_0$")
        ar.set(xlabel=r"$t$")
        ax.legend()
        fc.save(fig, "synthetic")
        for path, magic in ((os.path.join(out, "synthetic.pdf"), b"%PDF"),
                            (os.path.join(out, "synthetic.png"), b"\x89PNG"),
                            (os.path.join(docs, "synthetic.png"), b"\x89PNG")):
            try:
                with open(path, "rb") as f:
                    if f.read(4) != magic:
                        failures.append(f"save(): {path} is not a {magic[1:].decode()} file")
            except OSError:
                failures.append(f"save() did not write {os.path.basename(os.path.dirname(path))}/"
                                f"{os.path.basename(path)}")
        # save() refuses internal words in the texts of a figure
        for bad in ("DSMC (quick tier)", "restitution_model = 'constant'", "haff_cooling_alpha0.5.h5", "ERRATA §3"):
            fig, ax = plt.subplots()
            ax.plot([0, 1], [0, 1], label=bad)
            ax.legend()
            try:
                fc.save(fig, "refused")
                failures.append(f"save() accepted the legend {bad!r}")
            except ValueError:
                pass
        if glob.glob(os.path.join(out, "refused.*")):
            failures.append("save() wrote a refused figure")
        # a figure drawn from no run is marked so as a whole; a panel marked by no_dsmc() may name its runs
        if "synthetic" not in fc._current["no_dsmc"]:
            failures.append("save() did not mark a figure drawn from no run as without DSMC data")
        fig, ax = plt.subplots()
        fc.no_dsmc(ax, ["haff_cooling_alpha0.9", "velocity_shell"])
        try:
            fc.save(fig, "marked")
        except ValueError as e:
            failures.append(f"save() refused the mark of a panel without DSMC data: {e}")

        # every script: imported without touching the style, registers figures; each figure runs up to its
        # first missing input (no outputs, no granular-theory here) and fails in no other way
        fc.REGISTRY.clear()
        try:
            modules = load_scripts()
        except Exception as e:  # noqa: BLE001
            failures.append(f"a figure script does not import: {e!r}")
            modules = []
        if style_drift():
            failures.append(f"a script changes the style on import: {style_drift()}")
        for m in modules:
            if not any(f.module == m.__name__ for f in fc.REGISTRY):
                failures.append(f"{m.__name__}.py registers no figure (@figure)")
        stems = [s for f in fc.REGISTRY for s in f.stems]
        dup = sorted({s for s in stems if stems.count(s) > 1})
        if dup:
            failures.append(f"figures written by two functions: {dup}")
        missing_docs = sorted(set(DOCS_STEMS) - set(stems))
        if missing_docs:
            failures.append(f"DOCS_STEMS names figures no script draws: {missing_docs}")
        for f, status, d in fc.run_figures(fc.REGISTRY):
            if status != "missing":
                failures.append(f"{f.name} without inputs: {status} ({d.get('message', '').strip()[-400:]})")
            undocumented = sorted(set(d["asked"]) - documented_cases(sys.modules[f.module].__doc__))
            if undocumented:
                failures.append(f"{f.name} draws cases its script's --help does not list: {undocumented}")
        if style_drift():
            failures.append(f"a figure changes the style: {style_drift()}")
        print(f"checked {len(paths)} scripts, {len(fc.REGISTRY)} figure functions ({len(stems)} figures)")

    # the docs: every figure a page shows is in docs/figures/, is one make_all.py --docs writes, and is small
    import re
    shown = set()
    for page in glob.glob(os.path.join(ROOT, "docs", "*.md")):
        with open(page) as f:
            shown |= set(re.findall(r"\]\(figures/([^)]+)\.png\)", f.read()))
    for stem in sorted(shown):
        path = os.path.join(ROOT, "docs", "figures", stem + ".png")
        if stem not in DOCS_STEMS:
            failures.append(f"docs show figures/{stem}.png, which make_all.py --docs does not write (DOCS_STEMS)")
        if not os.path.exists(path):
            failures.append(f"docs show figures/{stem}.png, which is not in docs/figures/")
        elif os.path.getsize(path) > 150_000:
            failures.append(f"docs/figures/{stem}.png has {os.path.getsize(path)} bytes (> 150 kB)")
    print(f"checked {len(shown)} figures the docs show")

    for msg in failures:
        print("FAIL:", msg)
    if not failures:
        print("figure scripts: one style, PDF and PNG, no internal words in the synthetic check: OK")
    return 1 if failures else 0


def main():
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    try:
        import figures_common as fc  # answers --help itself, before it imports matplotlib
    except ImportError as e:
        print(f"{'SKIP' if '--check' in sys.argv else 'ERROR'}: {e} "
              "(install python3-matplotlib, python3-h5py, python3-numpy)")
        return SKIP if "--check" in sys.argv else 1
    args = fc.parse_command_line(sys.modules[__name__])
    return check() if args.check else generate(args)


if __name__ == "__main__":
    sys.exit(main())
