#!/usr/bin/env python3
"""The paper tier's reports and the pages generated from them (validation/reports/README.md).

usage:
  reports.py collect BUILD_DIR [--since ISO_DATE]
      copies the machine-readable reports (<case>.h5.report.json, written by every validation program)
      of the paper tier and of the cases docs/figures_spec.json names from BUILD_DIR/validation-output/
      (<stem>.report.json for the programs that run several variants)
      into validation/reports/<file stem>.json; --since skips reports older than the date (a stale
      report of a case that timed out in the run).
  reports.py figures [--check]
      writes docs/figures.md (one row per figure of the four papers) from docs/figures_spec.json and
      the reports; --check writes nothing and fails when the page differs from what it would write.
  reports.py quotes [--update] [PAGE ...]
      checks that every table a page generates from the reports (<!--reports-table ...-->) and every
      number it quotes from one, marked <!--r CASE "SUBSTRING" FIELD-->NUMBER, hold what the reports
      hold, at the precision written (default pages: README.md, docs/*.md, validation/*/README.md);
      --update rewrites them from the reports.
  reports.py check [--ctest BUILD_DIR]
      figures --check and quotes, every case the spec names in the index, and (with --ctest) the index
      listing BUILD_DIR's validation cases: the quick test docs.reports. Exit status 1 on any
      difference, 2 on a bad spec, table or mark.

Standard library only.
"""
import fnmatch
import glob
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REPORTS = os.path.join(ROOT, "validation", "reports")
SPEC = os.path.join(ROOT, "docs", "figures_spec.json")
FIGURES_PAGE = os.path.join(ROOT, "docs", "figures.md")
FIELDS = ("measured", "standard_error", "theory", "diff_se", "tolerance", "systematic", "z")


class Problem(Exception):
    """A bad spec, marker or command line: exit status 2."""


def load_reports():
    """{file stem: report} of validation/reports/ (index.json aside)."""
    reports = {}
    for path in sorted(glob.glob(os.path.join(REPORTS, "*.json"))):
        if os.path.basename(path) == "index.json":
            continue
        with open(path, encoding="utf-8") as f:
            reports[os.path.basename(path)[:-5]] = json.load(f)
    return reports


def load_index():
    """{case: {"labels": [...], "reports": [stems]}} of validation/reports/index.json (written by collect)."""
    path = os.path.join(REPORTS, "index.json")
    if not os.path.exists(path):
        raise Problem(f"{path}: missing (reports.py collect writes it)")
    with open(path, encoding="utf-8") as f:
        return json.load(f)["cases"]


def load_spec():
    with open(SPEC, encoding="utf-8") as f:
        spec = json.load(f)
    for row in spec:
        for key in ("figure", "caption", "parameters", "tests", "asserted", "tolerance", "key", "verdict"):
            if key not in row:
                raise Problem(f"{SPEC}: figure {row.get('figure', '?')}: no '{key}'")
    return spec


def owner(stem, names):
    """The case whose report `stem` is: the longest case name equal to it or followed by '_'."""
    best = None
    for name in names:
        if (stem == name or stem.startswith(name + "_")) and (best is None or len(name) > len(best)):
            best = name
    return best


def cases_of(patterns, names):
    """The case names (sorted, unique) that the spec's names or globs match."""
    out = []
    for pattern in patterns:
        out += [n for n in names if fnmatch.fnmatchcase(n, pattern) and n not in out]
    return sorted(out)


def ctest_cases(build_dir):
    """{case: labels} of the validation tests of a build tree (ctest --show-only=json-v1)."""
    text = subprocess.run([os.environ.get("CTEST", "ctest"), "--test-dir", build_dir, "--show-only=json-v1"], check=True,
                          capture_output=True, text=True).stdout
    cases = {}
    for test in json.loads(text)["tests"]:
        if not test["name"].startswith("validation."):
            continue
        labels = []
        for prop in test.get("properties", []):
            if prop["name"] == "LABELS":
                labels = prop["value"]
        cases[test["name"][len("validation."):]] = labels
    return cases


def collect(build_dir, since):
    cases = ctest_cases(build_dir)
    wanted = {n for n, labels in cases.items() if "paper" in labels}
    for row in load_spec():
        wanted.update(cases_of(row["tests"], cases))
    index = {n: {"labels": sorted(set(labels) - {"validation"}), "reports": []} for n, labels in sorted(cases.items())}
    old = load_reports()
    copied = skipped = 0
    for path in sorted(glob.glob(os.path.join(build_dir, "validation-output", "*.report.json"))):
        stem = re.sub(r"(\.h5)?\.report\.json$", "", os.path.basename(path))  # (programs of several runs: no .h5)
        case = owner(stem, cases)
        if case not in wanted:
            continue
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
        if since and report["date"] < since:
            print(f"skipped (dated {report['date']}, before {since}): {stem}")
            skipped += 1
            continue
        shutil.copyfile(path, os.path.join(REPORTS, stem + ".json"))
        index[case]["reports"].append(stem)
        copied += 1
    for stem in old:  # the report of an earlier run of a case that did not run now stays, as it was
        case = owner(stem, cases)
        if case is None:
            os.remove(os.path.join(REPORTS, stem + ".json"))
            print(f"removed the report of a case that no longer exists: {stem}")
        elif stem not in index[case]["reports"]:
            index[case]["reports"].append(stem)
    with open(os.path.join(REPORTS, "index.json"), "w", encoding="utf-8") as f:
        json.dump({"cases": index}, f, indent=1, sort_keys=True)
        f.write("\n")
    print(f"copied {copied} reports into {os.path.relpath(REPORTS, ROOT)}/, skipped {skipped}")
    for name in sorted(wanted):
        if not index[name]["reports"]:
            print(f"no report for the case {name}")


# ---------------------------------------------------------------------------------------- figures.md

def short(x, digits=4):
    return "n/a" if x is None else f"{x:.{digits}g}"


def result_cell(cases, index, reports, key):
    """'k/n cases pass' with the key check of the first case that has it, and the largest diff/tolerance."""
    if not cases:
        return "no case", ""
    stems = {c: sorted(index[c]["reports"]) for c in cases}
    ran = [c for c in cases if stems[c]]
    passing = [c for c in ran if all(reports[s]["failed"] == 0 for s in stems[c])]
    checks = [(s, ch) for c in ran for s in stems[c] for ch in reports[s]["checks"]]
    stated = sum(1 for _, ch in checks if ch.get("stated"))
    text = f"{len(passing)} of {len(ran)} cases run pass ({len(checks) - stated} checks"
    text += f", {stated} comparisons stated)" if stated else ")"
    if len(ran) < len(cases):
        text += f"; {len(cases) - len(ran)} of the {len(cases)} cases not in this run"
    failed = [c for c in ran if c not in passing]
    if failed:
        text += "; **failing**: " + ", ".join(f"`{c}`" for c in failed)
    ratios = [abs(ch["measured"] - ch["theory"]) / ch["tolerance"] for _, ch in checks
              if ch.get("tolerance") and ch.get("measured") is not None and ch.get("theory") is not None]
    if ratios:
        text += f"; largest \\|diff\\|/tolerance {max(ratios):.2f}"
    if key:
        for s, ch in checks:
            if key in ch["quantity"] and ch.get("measured") is not None:
                text += (f"; e.g. `{s}`: {short(ch['measured'])} +- {short(ch['standard_error'], 2)} against "
                         f"{short(ch['theory'])} ({short(ch['diff_se'], 2)} SE{', stated' if ch.get('stated') else ''})")
                break
    dates = [reports[s]["date"][:10] for c in ran for s in stems[c]]
    return text, (max(dates) if dates else "")


def cell_text(text, escape_pipes=True):
    """`text` for a Markdown table cell that Doxygen also reads: <, > and & as entities (outside code
    spans, a `<R_k^2>` would be taken for an HTML tag), | escaped."""
    parts = text.split("`")
    for i in range(0, len(parts), 2):  # outside the code spans
        parts[i] = parts[i].replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        if escape_pipes:
            parts[i] = parts[i].replace("|", "\\|")
    return "`".join(parts)


def figures_page(spec, reports):
    """The text of docs/figures.md."""
    lines = [
        "# The 35 figures of the four papers {#figures}",
        "",
        "Generated by `validation/reports/reports.py figures` from `docs/figures_spec.json` (what each figure",
        "is, the cases that reproduce it, what they assert) and the reports the paper tier wrote",
        "(`validation/reports/`, [how they are made](#figures_reports)); the quick test `docs.reports` fails when",
        "this page differs from what the script would write. Figures are numbered as in",
        "`paper-figures/README.md`: `000-1` is Fig. 1 of seed 000 (the DSMC notes), 001 Bodrova and Osinsky",
        "2024, 003 Montanero and Garzo 2002, 004 Montanero 2003. The ctest name of a case",
        "is `validation.` followed by its name; a name with `*` stands for every case it matches. The last",
        "result counts the cases whose reports hold no failed check, the largest |measured - theory| over the",
        "tolerance among all their checks, and one representative check (measured +- standard error over",
        "the replicas, the reference, the difference in standard errors).",
        "",
        "| figure | paper: quantity and parameters | cases | asserted | tolerance and its source | last result | date | as printed? |",
        "|---|---|---|---|---|---|---|---|",
    ]
    index = load_index()
    for row in spec:
        cases = cases_of(row["tests"], index)
        result, date = result_cell(cases, index, reports, row["key"])
        tests = ", ".join(f"`{t}`" for t in row["tests"]) or "none"
        cells = [f"{row['figure']}", f"{row['caption']}; {row['parameters']}", tests, row["asserted"],
                 row["tolerance"], result, date, row["verdict"]]
        lines.append("| " + " | ".join(cell_text(c, escape_pipes=i != 5) for i, c in enumerate(cells)) + " |")
    lines += [
        "",
        "## How the reports are made {#figures_reports}",
        "",
        "Every validation program writes, beside `<case>.h5.report.txt`, `<case>.h5.report.json`: each check",
        "with its measured value, standard error, reference, tolerance (z SE + systematic allowance), the",
        "build's version and the date. After a paper-tier run on 2 cores",
        "",
        "```sh",
        "ctest --test-dir build -L paper -j2",
        "python3 validation/reports/reports.py collect build --since YYYY-MM-DD   # the run's start",
        "python3 validation/reports/reports.py figures                          # this page",
        "python3 validation/reports/reports.py quotes --update                  # numbers quoted in pages",
        "```",
        "",
        "and the reports are committed with the pages. The numbers pages quote from a report carry an",
        "invisible mark, `<!--r CASE \"SUBSTRING\" FIELD-->NUMBER`, which `docs.reports` checks against the",
        "report at the precision written (validation/reports/README.md).",
        "",
    ]
    return "\n".join(lines)


def figures(check):
    spec = load_spec()
    if len(spec) != 35:
        raise Problem(f"{SPEC}: {len(spec)} figures, not 35")
    text = figures_page(spec, load_reports())
    old = open(FIGURES_PAGE, encoding="utf-8").read() if os.path.exists(FIGURES_PAGE) else ""
    if check:
        if old != text:
            print("docs/figures.md is not what reports.py figures writes from docs/figures_spec.json and "
                  "validation/reports/: run `python3 validation/reports/reports.py figures`")
            return 1
        return 0
    with open(FIGURES_PAGE, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"wrote {os.path.relpath(FIGURES_PAGE, ROOT)} ({len(spec)} figures)")
    return 0


# ------------------------------------------------------------------------------------------ quotes

MARK = re.compile(r'<!--r\s+(\S+)\s+"([^"]*)"\s+(\w+)\s*-->([-+]?[0-9]+(?:\.[0-9]+)?(?:[eE][-+]?[0-9]+)?)')


def written_like(value, text):
    """`value` written with the precision of `text` (decimals, or the mantissa's in e-notation), with a
    `+` before a positive value where `text` has one."""
    plus = "+" if text.startswith("+") else ""
    if "e" in text.lower():
        mantissa = text.lower().split("e")[0]
        digits = len(mantissa.split(".")[1]) if "." in mantissa else 0
        m, e = f"{value:.{digits}e}".split("e")
        return f"{plus if value >= 0 else ''}{m}e{int(e)}"
    digits = len(text.split(".")[1]) if "." in text else 0
    return f"{plus if value >= 0 else ''}{value:.{digits}f}"


NUMBER = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")


def quoted_value(reports, case, substring, field, where):
    """The number `field` of the one check (or else note) of report `case` whose text holds `substring`:
    a field of the check, `gap_percent` = 100 (theory - measured)/measured, or `textN`, the N-th number
    written in the check's or note's text."""
    if case not in reports:
        raise Problem(f"{where}: no report '{case}' in validation/reports/")
    matches = [ch for ch in reports[case]["checks"] if substring in ch["quantity"]]
    if not matches:
        matches = [{"quantity": note} for note in reports[case].get("notes", []) if substring in note]
    if len(matches) != 1:
        raise Problem(f"{where}: report '{case}' has {len(matches)} checks or notes whose text holds \"{substring}\"")
    check = matches[0]
    if re.fullmatch(r"text[1-9][0-9]*", field):
        numbers = NUMBER.findall(check["quantity"])
        index = int(field[4:]) - 1
        if index >= len(numbers):
            raise Problem(f"{where}: the text \"{check['quantity']}\" of '{case}' has {len(numbers)} numbers, not {index + 1}")
        return float(numbers[index])
    if field == "gap_percent" and check.get("measured") and check.get("theory") is not None:
        return 100.0 * (check["theory"] - check["measured"]) / check["measured"]
    if field not in FIELDS or check.get(field) is None:
        raise Problem(f"{where}: the check \"{substring}\" of '{case}' has no number '{field}'")
    return check[field]


def quotes(pages, update):
    reports = load_reports()
    differ = marks = 0
    for page in pages:
        original = open(page, encoding="utf-8").read()
        text = tables(original, reports, page)
        if text != original:
            differ += 1
            if not update:
                print(f"{os.path.relpath(page, ROOT)}: a generated table differs from its reports")
        out, last = [], 0
        code = in_code(text)
        for m in MARK.finditer(text):
            if code(m.start()):
                continue
            line = text.count("\n", 0, m.start()) + 1
            where = f"{os.path.relpath(page, ROOT)}:{line}"
            value = quoted_value(reports, m.group(1), m.group(2), m.group(3), where)
            page_text = m.group(4)
            report_text = written_like(value, page_text)
            marks += 1
            if float(report_text) != float(page_text):
                differ += 1
                if not update:
                    print(f"{where}: quotes {page_text} for {m.group(3)} of \"{m.group(2)}\" in '{m.group(1)}'; "
                          f"the report holds {value!r} ({report_text} as written)")
            out.append(text[last:m.start(4)] + report_text)
            last = m.end(4)
        unparsed = [m.start() for m in re.finditer(r"<!--r\s", text) if not code(m.start())]
        if len(unparsed) != len([m for m in MARK.finditer(text) if not code(m.start())]):
            raise Problem(f"{os.path.relpath(page, ROOT)}: a mark '<!--r ...-->' not followed directly by a number "
                          "(written as 1.23, -4.5e-6 or +0.7)")
        out.append(text[last:])
        if update and "".join(out) != original:
            with open(page, "w", encoding="utf-8") as f:
                f.write("".join(out))
            print(f"updated {os.path.relpath(page, ROOT)}")
    print(f"{marks} quoted numbers in {len(pages)} pages; {differ} differ from their reports")
    return 1 if differ and not update else 0


TABLE = re.compile(r"<!--reports-table\n(.*?)-->\n(.*?)<!--/reports-table-->", re.S)


def table_row(reports, label, case, substring, where):
    """One row of a generated table: the check of `case` whose quantity holds `substring`."""
    if case not in reports:
        raise Problem(f"{where}: no report '{case}' in validation/reports/")
    matches = [ch for ch in reports[case]["checks"] if substring in ch["quantity"]]
    if len(matches) != 1:
        raise Problem(f"{where}: report '{case}' has {len(matches)} checks whose quantity holds \"{substring}\"")
    ch = matches[0]
    date = reports[case]["date"][:10]
    if ch.get("measured") is None:  # a condition
        cells = [ch["quantity"], "", "", "passes" if ch["pass"] else "**fails**"]
    else:
        measured = f"{short(ch['measured'], 6)} +- {short(ch['standard_error'], 2)}"
        diff = f"{short(ch['diff_se'], 2)} SE"
        if ch.get("stated"):
            verdict = "stated"
        else:
            verdict = (f"{short(ch['z'], 2)} SE + {short(ch['systematic'], 2)}: " +
                       ("passes" if ch["pass"] else "**fails**"))
        cells = [measured, short(ch["theory"], 6), diff, verdict]
    return "| " + " | ".join(cell_text(c) for c in [label] + cells + [f"`{case}`, {date}"]) + " |"


CODE = re.compile(r"^[ \t]*```.*?^[ \t]*```|`[^`\n]*`", re.S | re.M)


def in_code(text):
    """A test whether a position of `text` lies in a code fence or span (examples, not quotes)."""
    spans = [m.span() for m in CODE.finditer(text)]
    return lambda pos: any(a <= pos < b for a, b in spans)


def tables(text, reports, page):
    """`text` with every generated table (<!--reports-table ROWS-->...<!--/reports-table-->) rewritten from
    the reports. ROWS: one line each, `label | case | substring of the check's quantity`."""
    code = in_code(text)

    def render(m):
        if code(m.start()):
            return m.group(0)
        where = f"{os.path.relpath(page, ROOT)}:{text.count(chr(10), 0, m.start()) + 1}"
        rows = ["| check | measured +- SE | reference | difference | tolerance | report |", "|---|---|---|---|---|---|"]
        for line in m.group(1).strip().splitlines():
            parts = [x.strip() for x in line.split("|")]
            if len(parts) != 3:
                raise Problem(f"{where}: a table row is 'label | case | substring', not '{line}'")
            rows.append(table_row(reports, *parts, where))
        return f"<!--reports-table\n{m.group(1)}-->\n" + "\n".join(rows) + "\n<!--/reports-table-->"
    return TABLE.sub(render, text)


def default_pages():
    return sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")) +
                  glob.glob(os.path.join(ROOT, "validation", "*", "README.md")) + [os.path.join(ROOT, "README.md")])


def check(build_dir):
    status = figures(check=True)
    status |= quotes(default_pages(), update=False)
    index = load_index()
    for row in load_spec():
        for pattern in row["tests"]:
            if not cases_of([pattern], index):
                print(f"docs/figures_spec.json: figure {row['figure']}: no case '{pattern}' in validation/reports/index.json")
                status = 1
    if build_dir:
        names = ctest_cases(build_dir)
        if sorted(names) != sorted(index):
            print("validation/reports/index.json lists other cases than ctest (run reports.py collect): "
                  f"only in ctest {sorted(set(names) - set(index))[:5]}, only in the index {sorted(set(index) - set(names))[:5]}")
            status = 1
    return status


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    command, args = argv[1], argv[2:]
    try:
        if command == "collect" and args:
            since = args[args.index("--since") + 1] if "--since" in args else ""
            collect(args[0], since)
            return 0
        if command == "figures":
            return figures(check="--check" in args)
        if command == "quotes":
            pages = [a for a in args if a != "--update"] or default_pages()
            return quotes(pages, update="--update" in args)
        if command == "check":
            return check(args[args.index("--ctest") + 1] if "--ctest" in args else "")
    except Problem as problem:
        print(f"reports.py: {problem}", file=sys.stderr)
        return 2
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
