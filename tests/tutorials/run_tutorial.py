#!/usr/bin/env python3
"""Runs the commands of one tutorial page as written and checks what they print (ctest `tutorial.*`).

usage: run_tutorial.py SOURCE_DIR BIN_DIR TUTORIAL WORK_DIR

TUTORIAL is a folder of examples/ (e.g. 01-haff-cooling). The page's ```sh blocks are run line by line
(a line ending in a backslash continues; the first block from the repository root, later blocks from
the tutorial's folder, where the page's reader is) in a copy of the repository's layout under WORK_DIR:
WORK_DIR/<tutorial>/examples/<tutorial> holds a copy of the tutorial and of examples/*.py, and
WORK_DIR/<tutorial>/build/bin links to BIN_DIR, so that `cd examples/NN-name` and `../../build/bin/...`
work unchanged. Only the size differs: in the copied namelists n_particles is divided by 25 (at least
2000) and replicas is at most 2, except where the page depends on the run's duration (tutorial 05 kills a
run after 3 s to show the restart), which keeps its size.

Checks, per command: exit status 0 (`timeout -s KILL` lines: 137, or 0 when the run ended before the
kill, and then the restart that follows is skipped with a note; a restart whose checkpoint the kill
came too early to leave is skipped with the rest of its block, with a note); `granular-dsmc --table` prints CSV with
a header, at least one row, the same number of fields on every line and no NaN or Inf outside `_error`
columns; `> X.json` writes JSON; `&& echo identical` prints `identical`. Lines that need a cluster (`srun`)
are not run; `mpirun` lines and the plotting script are skipped, with a note, when mpirun or matplotlib
is missing. Exit status 1 with every failure listed, else 0.
"""
import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys

REDUCE = 25           # n_particles / REDUCE, at least MIN_PARTICLES
MIN_PARTICLES = 2000
MAX_REPLICAS = 2
FULL_SIZE = {"05-sweeps-mpi-checkpoints"}  # the page times a kill: the run must last as it says
SMALLER_REDUCTION = {"03-polydisperse-lowrank": 5}  # 200 species: at least 2 particles of the rarest


def blocks(page):
    """The page's ```sh blocks, each a list of commands: continuation lines joined, comments and blanks
    dropped."""
    out, block, pending = [], False, ""
    for line in open(page, encoding="utf-8"):
        line = line.rstrip("\n")
        if line.startswith("```"):
            block = line.strip() == "```sh" and not block
            if block:
                out.append([])
            continue
        if not block:
            continue
        if line.endswith("\\"):
            pending += line[:-1] + " "
            continue
        text = (pending + line).strip()
        pending = ""
        if text and not text.startswith("#"):
            out[-1].append(text)
    return [b for b in out if b]


def reduce_namelist(path, reduce):
    text = open(path, encoding="utf-8").read()
    text = re.sub(r"(?im)^(\s*n_particles\s*=\s*)(\d+)",
                  lambda m: m.group(1) + str(max(MIN_PARTICLES, int(m.group(2)) // reduce)), text)
    text = re.sub(r"(?im)^(\s*replicas\s*=\s*)(\d+)",
                  lambda m: m.group(1) + str(min(MAX_REPLICAS, int(m.group(2)))), text)
    open(path, "w", encoding="utf-8").write(text)


def prepare(source, bin_dir, tutorial, work):
    root = os.path.join(work, tutorial)
    shutil.rmtree(root, ignore_errors=True)
    examples = os.path.join(root, "examples")
    shutil.copytree(os.path.join(source, "examples", tutorial), os.path.join(examples, tutorial),
                    ignore=shutil.ignore_patterns("*.png", "*.h5", "*.json"))
    for name in os.listdir(os.path.join(source, "examples")):
        if name.endswith(".py"):
            shutil.copy(os.path.join(source, "examples", name), examples)
    os.makedirs(os.path.join(root, "build"))
    os.symlink(os.path.abspath(bin_dir), os.path.join(root, "build", "bin"))
    if tutorial not in FULL_SIZE:
        for name in os.listdir(os.path.join(examples, tutorial)):
            if name.endswith(".nml"):
                reduce_namelist(os.path.join(examples, tutorial, name), SMALLER_REDUCTION.get(tutorial, REDUCE))
    return root


def has_matplotlib(python):
    return shutil.which(python) and subprocess.run([python, "-c", "import matplotlib, h5py, numpy"],
                                                   capture_output=True).returncode == 0


def check_table(out):
    """What is wrong with the CSV `out` of --table (None: nothing)."""
    rows = list(csv.reader(io.StringIO(out)))
    if len(rows) < 2:
        return "--table printed no row"
    header = rows[0]
    if len(set(header)) != len(header):
        return "--table: repeated column names"
    for row in rows[1:]:
        if len(row) != len(header):
            return f"--table: a row of {len(row)} fields under a header of {len(header)}"
        for name, field in zip(header, row):
            if not name.endswith("_error") and field.lower() in ("nan", "inf", "-inf"):
                return f"--table: {name} = {field}"
    return None


def run(tutorial, root, page_blocks, env):
    """Runs the blocks: the first from the repository root (it starts with `cd examples/NN-name`), every
    later one from the tutorial's folder, as the page's reader would. (failures, notes)"""
    state = {"failures": [], "notes": [], "skip_restart": False, "no_checkpoint": False,
             "python_ok": has_matplotlib("/usr/bin/python3"), "env": env}
    for block in page_blocks:
        state["no_checkpoint"] = False
        cwd = root if block[0].startswith("cd examples/") else os.path.join(root, "examples", tutorial)
        for command in block:
            cwd = run_command(command, cwd, state)
    return state["failures"], state["notes"]


def skipped(command, cwd, state):
    """Why `command` is not run here, or None."""
    if command.startswith("srun"):
        return "needs a cluster"
    if "mpirun" in command and not shutil.which("mpirun"):
        return "no mpirun"
    if "plot_tutorial.py" in command and not state["python_ok"]:
        return "no matplotlib, h5py and numpy for /usr/bin/python3"
    if state["skip_restart"] and "--restart" in command:
        return "the run before it ended before the kill"
    if state["no_checkpoint"]:
        return "the kill came before the first checkpoint (a busy machine): nothing to resume"
    restart = re.search(r"--restart\s+(\S+)", command)
    if restart and not os.path.exists(os.path.join(cwd, restart.group(1))):
        state["no_checkpoint"] = True  # and the rest of the block, which compares the resumed run
        return "the kill came before the first checkpoint (a busy machine): nothing to resume"
    return None


def run_command(command, cwd, state):
    """Runs one command in `cwd`, checks it (failures and notes go to `state`); the directory it ends in."""
    failures, notes = state["failures"], state["notes"]
    why = skipped(command, cwd, state)
    if why:
        notes.append(f"not run ({why}): {command}")
        return cwd
    marker = "@@cwd@@"
    p = subprocess.run(["bash", "-c", f"{command}\nstatus=$?\necho {marker}$PWD\nexit $status"], cwd=cwd,
                       capture_output=True, text=True, env=state["env"], timeout=600)
    out, _, new_cwd = p.stdout.rpartition(marker)
    cwd = new_cwd.strip() or cwd
    status = p.returncode
    what = f"`{command}` (exit {status})"
    if command.startswith("timeout -s KILL"):
        if status == 0:
            state["skip_restart"] = True
            notes.append(f"the run ended before the kill: {command}")
        elif status != 137:
            failures.append(f"{what}: expected 137 (killed)\n{p.stderr}")
        return cwd
    if status != 0:
        failures.append(f"{what}\n{p.stderr}")
        return cwd
    if "--table" in command and "|" not in command:
        problem = check_table(out)
        if problem:
            failures.append(f"{what}: {problem}\n{out[:2000]}")
    if "|" in command and not out.strip():
        failures.append(f"{what}: printed nothing")
    if "echo identical" in command and "identical" not in out:
        failures.append(f"{what}: did not print 'identical'")
    written = re.search(r">\s*(\S+\.json)", command)
    if written:
        try:
            with open(os.path.join(cwd, written.group(1)), encoding="utf-8") as f:
                json.load(f)
        except (OSError, ValueError) as e:
            failures.append(f"{what}: {written.group(1)} is not JSON: {e}")
    return cwd


def main(argv):
    if len(argv) != 5 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) == 2 else 2
    source, bin_dir, tutorial, work = argv[1:]
    page = os.path.join(source, "examples", tutorial, "README.md")
    page_blocks = blocks(page)
    if not page_blocks:
        print(f"{page}: no ```sh commands")
        return 1
    root = prepare(source, bin_dir, tutorial, work)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", MPLBACKEND="Agg")
    failures, notes = run(tutorial, root, page_blocks, env)
    for note in notes:
        print("note:", note)
    print(f"{tutorial}: {sum(map(len, page_blocks))} commands, {len(failures)} failed")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
