#!/usr/bin/python3
"""Runs the commands of the manual (README.md, docs/*.md) so that none can rot.

  run_doc_commands.py --source TREE --build BUILD [--python EXE] --work DIR PAGE.md
      Runs every code block of PAGE.md in order in the fresh scratch folder DIR (which gets
      `examples`, `bench`, `tests` and `build` as links into the tree and the build, and an empty
      `docs/images`, so commands that make the docs' pictures write there), with the build's
      `aggpack` and `aggpack-gui` first on PATH and its Python module on PYTHONPATH:
        ```sh / ```bash / ```shell   every line (backslash continuations joined) is a command,
                                      run by bash (aggpack-gui under xvfb-run);
        ```console                    lines starting with "$ " are commands, the rest is output;
        ```python                     the block runs as one script;
        ```toml [NAME.toml]           the block must parse as TOML; with a name it is written to
                                      that file for the commands after it.
      A command must exit 0, unless it ends with the comment `# exit N` or `# exit N: TEXT`
      (then it must exit N, and TEXT must be in its stderr).
  run_doc_commands.py --source TREE --check PAGE.md ...
      The static checks over all pages: every relative link and image points to an existing file
      (and heading, for a #fragment), no internal issue numbers ("issue 14", "#27"), every fenced
      block has a language this script knows, every command's program is one it knows how to run
      (KNOWN_PROGRAMS) or is in SKIP, no command-looking line sits in a block that is not run (an
      indented block, or a ```text block without a placeholder such as FILE, [OPTIONS], <N> or
      a|b: synopses are text, examples are ```sh), and every FAST and SKIP entry still matches a
      command of the pages.

Long commands run smaller through FAST (below): the command as written -> arguments appended
(and replacements) for the test. They still run the real command path (same subcommand, same
config file), only on a smaller case. SKIP lists the few commands that install or build things.
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tomllib

from markdown_it import MarkdownIt

# A small trough (the golden test's, tests/cli/cases/repose/trough.toml): 0.35 m long, 6.25 mm
# particles, stage times of a few hundredths of a second. About a second of CPU per run; the
# angle it measures means nothing, the run goes through every stage and writes every file.
SMALL_TROUGH = ("--set trough.length=0.35 --set trough.width=0.063 --set trough.height=0.1 "
                "--set trough.baffle_position=0.151 --set trough.baffle_thickness=0.005 "
                "--set trough.baffle_speed=0.11 --set trough.baffle_clear_time=0.045 "
                "--set particle.radius=0.00625 --set particle.edge_length=0.00625 "
                "--set particle.fill_height=0.025 --set physics.density=1200 "
                "--set rest.quiet_time=0.05 --set rest.check_interval=0.005 "
                "--set rest.max_time=0.02 --set rest.confirm_window=0.5")
# The command as written in the markdown -> how the test runs it smaller: "append" is added to
# its arguments, "replace" swaps (old, new) pieces of it (e.g. a seed range). Each entry says why.
FAST = {
    # 100,000 particles: ~4 s of CPU; 5,000 show the same command.
    "aggpack shapes -n 100000 --alpha 0.7 -o shapes.csv": {"replace": [("100000", "5000")]},
    # the whole pytest suite (~40 s): one file of it, run the same way
    "PYTHONPATH=build/python AGGPACK_BINARY=build/aggpack AGGPACK_BUILD_DIR=build python3 -m pytest "
    "tests/python -q": {"replace": [("tests/python -q", "tests/python/test_errors.py -q")]},
    # the paper's repose test (1,050 particles, minutes) in the small trough
    "aggpack repose -o repose-out": {"append": SMALL_TROUGH},
    "aggpack repose examples/repose-acrylic-048.toml --seeds 1-16 -j 2 -o ens048": {
        "replace": [("1-16", "1-2")], "append": SMALL_TROUGH},
    "aggpack repose examples/repose-acrylic-048.toml --seeds 1-4 --case 1 --of 2 -o ens": {
        "append": SMALL_TROUGH},
    "aggpack repose examples/repose-acrylic-048.toml --seeds 1-4 --case 2 --of 2 -o ens": {
        "append": SMALL_TROUGH},
    "aggpack repose examples/repose-acrylic-075.toml -o acrylic-075": {
        "append": SMALL_TROUGH},
    "seq 1 2 | xargs -P 2 -I{} aggpack repose examples/repose-acrylic-048.toml --seeds 1-4 "
    "--case {} --of 2 -o ens2 --progress none": {"append": SMALL_TROUGH},
    "mpirun -n 2 aggpack sweep examples/sweep-acrylic-trends.toml --seeds 1-2 -j 1 -o sw "
    "--progress none": {"append": SMALL_TROUGH + " --set sweep.alphas=[0.6] "
                                  "--set sweep.frictions=[0.3,0.5]"},
    "aggpack sweep -o sweep-out -j 2": {  # 65 cases of 1-2 CPU minutes: 2 small ones
        "append": SMALL_TROUGH + " --set sweep.alphas=[0.5] --set sweep.frictions=[0.2,0.4]"},
    # gravity settling of 199 particles (~14 s of CPU): a 30 mm cube of the same grading
    "aggpack pack examples/concrete-fuller.toml --set container.length=0.05 "
    "--set container.width=0.05 --set container.depth=0.05 -o cube50.h5": {
        "replace": [("0.05", "0.03")]},
    # 3,909 particles densified (~8 s of CPU): the same file's run into a 40 mm cube
    "aggpack pack examples/dense-fuller.toml -o dense-fuller.h5": {
        "append": "--set container.length=0.04 --set container.width=0.04 "
                  "--set container.depth=0.04 --set densify.max_sweeps=100"},
    "aggpack pack examples/dense-bed.toml -o dense-bed.h5": {
        "append": "--set densify.max_sweeps=100"},
    "aggpack densify lattice.h5 -o lattice-bed.h5 --mode bed --sweeps 10000": {
        "replace": [("10000", "20")]},
    # the mesomodel of the whole 100 mm cube is ~10^6 tetrahedra: a 40 mm cube
    "aggpack pack examples/concrete-fuller.toml --set container.wall_gap=0.0002 "
    "--set packer.gap=0.0005 -o c.h5": {
        "append": "--set container.length=0.04 --set container.width=0.04 "
                  "--set container.depth=0.04"},
    # the periodic RVE homogenised at 2 mm edges (~30 s of CPU) and its cut: 4 mm edges
    "aggpack mesomodel rve.h5 -o rve.inp --homogenize --solver iterative --mortar-size 0.002 "
    "--aggregate-size 0.002": {"replace": [("0.002", "0.004")]},
    "aggpack render rve.h5 --mesomodel-cut z=0.02 --mortar-size 0.002 --aggregate-size 0.002 "
    "-o rve-cut.png": {"replace": [("0.002", "0.004")]},
    # 256 voxels along the cube: ~14 s of CPU; 64 (the .vti line's size) in a fraction of that
    "aggpack mesomodel voxel.h5 --voxels 256 --itz 0.0005 -o c.raw": {"replace": [("256", "64")]},
}

# Commands that are not run, each with the reason. Keep it short.
SKIP = {
    "scripts/quickstart.sh": "installs Debian packages and builds (the test runs on the build)",
    "scripts/test.sh": "installs Debian packages, builds and runs every test (this one included)",
    "scripts/package.sh": "builds the Debian package (CI's package test runs it)",
    "apt install ./build/aggpack_0.1.0_amd64.deb": "installs (CI's scripts/package-test.sh)",
    "apt-get install fonts-noto-cjk": "installs a Debian package",
}

# Programs the test knows how to run (with the build's aggpack first on PATH).
KNOWN_PROGRAMS = {"aggpack", "aggpack-gui", "python3", "gnuplot", "mkdir", "seq", "xargs", "mpirun",
                  "bench/compare_densify.sh"}

RUN_LANGS = {"sh", "bash", "shell", "console"}
OTHER_LANGS = {"python", "toml", "text", "csv", "json", "ini"}
COMMAND_LIKE = re.compile(r"^\s*(\$ )?([A-Z_]+=\S+\s+)*(aggpack|aggpack-gui|python3|ccx|yade|gnuplot"
                          r"|mpirun|apt|apt-get|cmake|ctest|sbatch)(\s|$)|^\s*(scripts|bench|build)/")
PLACEHOLDER = re.compile(r"<\w+>|\[|\||\.\.\.|\b[A-Z][A-Z_0-9]{1,}\b")
ISSUE_NUMBER = re.compile(r"\bissues? \d+|(?<![\w&/])#\d+\b", re.IGNORECASE)
EXIT_COMMENT = re.compile(r"\s#\s*exit (\d+)(?::\s*(.*\S))?\s*$")


def blocks(path, with_info=False):
    """(kind, language, text, line[, info string]) of every code block in a markdown file."""
    with open(path, encoding="utf-8") as f:
        tokens = MarkdownIt("commonmark").parse(f.read())
    for t in tokens:
        if t.type == "fence":
            block = ("fence", t.info.strip().split(" ")[0], t.content, t.map[0] + 1)
        elif t.type == "code_block":
            block = ("indented", "", t.content, t.map[0] + 1)
        else:
            continue
        yield block + (t.info.strip(),) if with_info else block


def commands(info, text):
    """The command lines of a runnable block (continuations joined, comments and output out)."""
    lines, current = [], ""
    for raw in text.splitlines():
        if info == "console":
            if current == "" and not raw.startswith("$ "):
                continue  # output
            raw = raw[2:] if current == "" else raw
        line = raw.rstrip()
        if current == "" and (not line.strip() or line.lstrip().startswith("#")):
            continue
        if line.endswith("\\"):
            current += line[:-1].rstrip() + " "
            continue
        lines.append((current + line.strip()).strip())
        current = ""
    if current:
        lines.append(current.strip())
    return lines


def strip_comment(command):
    """The command without a trailing `# ...` comment (outside quotes), and the expected exit."""
    expected = (0, None)
    m = EXIT_COMMENT.search(command)
    if m:
        expected = (int(m.group(1)), m.group(2))
    quote = None
    for i, c in enumerate(command):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or command[i - 1].isspace()):
            return command[:i].strip(), expected
    return command.strip(), expected


def program_of(command):
    """The program of a command (after VAR=value words); of its first stage in a pipeline."""
    words = shlex.split(command.split("|")[0])
    while words and re.match(r"^[A-Za-z_][A-Za-z_0-9]*=", words[0]):
        words = words[1:]
    if not words:
        return ""
    return words[0] if words[0].startswith(("bench/", "scripts/")) else os.path.basename(words[0])


def programs_of(command):
    """Every program of a command: each pipeline stage's, and the one xargs runs."""
    found = []
    for stage in command.split("|"):
        program = program_of(stage)
        found.append(program)
        if program == "xargs":
            words = shlex.split(stage)
            rest = [w for w in words[1:] if not w.startswith("-") and w not in ("4", "2", "{}")]
            found.append(os.path.basename(rest[0]) if rest else "")
        if program == "mpirun":
            words = shlex.split(stage)
            found.append(next((w for w in words[1:] if not w.startswith("-") and
                               not w.isdigit()), ""))
    return found


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def anchors(path):
    with open(path, encoding="utf-8") as f:
        tokens = MarkdownIt("commonmark").parse(f.read())
    found = set()
    for i, t in enumerate(tokens):
        if t.type == "heading_open":
            found.add(slug(tokens[i + 1].content.replace("`", "")))
    return found


def check_page(path, source, problems):
    rel = os.path.relpath(path, source)
    text = open(path, encoding="utf-8").read()
    for n, line in enumerate(text.splitlines(), 1):
        m = ISSUE_NUMBER.search(line)
        if m:
            problems.append(f"{rel}:{n}: internal issue number '{m.group(0)}'")
    tokens = MarkdownIt("commonmark").parse(text)
    for t in tokens:
        for child in (t.children or []):
            target = child.attrs.get("href") if child.type == "link_open" else (
                child.attrs.get("src") if child.type == "image" else None)
            if not target or re.match(r"^[a-z]+:", target):
                continue
            name, _, fragment = target.partition("#")
            file = os.path.normpath(os.path.join(os.path.dirname(path), name)) if name else path
            if not os.path.exists(file):
                problems.append(f"{rel}:{t.map[0] + 1}: link to a missing file: {target}")
            elif fragment and file.endswith(".md") and fragment not in anchors(file):
                problems.append(f"{rel}:{t.map[0] + 1}: link to a missing heading: {target}")
    for kind, info, content, line in blocks(path):
        where = f"{rel}:{line}"
        if kind == "indented" or info not in RUN_LANGS:
            if kind == "fence" and info not in OTHER_LANGS:
                problems.append(f"{where}: a ``` block with language '{info}' the test does not "
                                f"know (runs: {sorted(RUN_LANGS)}; not run: {sorted(OTHER_LANGS)})")
                continue
            if info in ("python", "toml"):
                continue
            for cl in content.splitlines():
                if COMMAND_LIKE.match(cl) and not PLACEHOLDER.search(cl):
                    problems.append(f"{where}: a command in a block that is not run "
                                    f"(make it a ```sh block): {cl.strip()}")
            continue
        for command in commands(info, content):
            bare, _ = strip_comment(command)
            if bare in SKIP:
                continue
            unknown = [p for p in programs_of(bare) if p not in KNOWN_PROGRAMS]
            if unknown:
                problems.append(f"{where}: the test does not know how to run {unknown}: {bare}")


def fast(command):
    rule = FAST.get(command)
    if not rule:
        return command
    for old, new in rule.get("replace", []):
        if old not in command:
            raise SystemExit(f"FAST rule for '{command}': '{old}' not in it")
        command = command.replace(old, new)
    if rule.get("append"):
        command += " " + rule["append"]
    return command


def run_page(path, source, build, python, work):
    rel = os.path.relpath(path, source)
    os.makedirs(work, exist_ok=True)
    for entry in os.listdir(work):  # a fresh folder each run
        subprocess.run(["rm", "-rf", os.path.join(work, entry)], check=True)
    for name in ("examples", "bench", "tests"):
        os.symlink(os.path.join(source, name), os.path.join(work, name))
    os.symlink(build, os.path.join(work, "build"))
    os.makedirs(os.path.join(work, "docs", "images"))
    env = dict(os.environ)
    env["PATH"] = f"{build}:{env.get('PATH', '/usr/bin:/bin')}"
    env["PYTHONPATH"] = os.path.join(build, "python")
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    env["LANG"] = "C.UTF-8"
    env.pop("LC_ALL", None)
    env.pop("LC_MESSAGES", None)
    # mpirun in a container runs as root, on 2 cores: allowed, and oversubscribed if need be
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    ran, used = 0, set()
    failures = []
    for kind, info, content, line, full_info in blocks(path, with_info=True):
        if kind != "fence":
            continue
        where = f"{rel}:{line}"
        if info == "toml":  # ```toml NAME.toml: written to NAME.toml for the commands after it
            try:
                tomllib.loads(content)
            except tomllib.TOMLDecodeError as e:
                failures.append(f"{where}: TOML block does not parse: {e}")
            words = full_info.split()
            if len(words) > 1:
                with open(os.path.join(work, words[1]), "w", encoding="utf-8") as f:
                    f.write(content)
            continue
        if info == "python":
            todo = [(f"[python block of {where}]", [python, "-c", content], (0, None))]
        elif info in RUN_LANGS:
            todo = []
            for command in commands(info, content):
                bare, expected = strip_comment(command)
                if bare in SKIP:
                    print(f"skip {where}: {bare}  ({SKIP[bare]})")
                    continue
                if bare in FAST:
                    used.add(bare)
                run = fast(bare)
                if program_of(run) == "aggpack-gui":  # under a virtual X server, after VAR=...
                    m = re.match(r"^(\s*(?:[A-Za-z_][A-Za-z_0-9]*=\S+\s+)*)(.*)$", run)
                    run = m.group(1) + "xvfb-run -a -s '-screen 0 1280x800x24' " + m.group(2)
                if program_of(run) == "python3":
                    run = re.sub(r"\bpython3\b", python, run, count=1)
                todo.append((command, ["bash", "-o", "pipefail", "-c", run], expected))
        else:
            continue
        for shown, argv, expected in todo:
            t0 = os.times()
            p = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True)
            t1 = os.times()
            cpu = (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)
            ran += 1
            print(f"[{cpu:6.2f} s CPU] exit {p.returncode}  {where}: {shown}")
            status, message = expected
            if p.returncode != status or (message and message not in p.stderr):
                failures.append(f"{where}: exit {p.returncode} (expected {status}"
                                f"{', stderr with: ' + message if message else ''}): {shown}\n"
                                f"--- argv: {argv}\n--- stdout:\n{p.stdout[-3000:]}\n"
                                f"--- stderr:\n{p.stderr[-3000:]}")
    return ran, failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build")
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--work")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("pages", nargs="+")
    a = ap.parse_args()
    source = os.path.abspath(a.source)
    pages = [os.path.abspath(p) for p in a.pages]
    if a.check:
        problems = []
        for page in pages:
            check_page(page, source, problems)
        used = set()
        for page in pages:
            for kind, info, content, line in blocks(page):
                if kind == "fence" and info in RUN_LANGS:
                    used.update(strip_comment(c)[0] for c in commands(info, content))
        for table, entries in (("FAST", FAST), ("SKIP", SKIP)):
            for command in entries:
                if command not in used:
                    problems.append(f"{table} entry matches no command of the pages: {command}")
        for p in problems:
            print(p)
        print(f"{len(pages)} pages checked, {len(problems)} problems")
        return 1 if problems else 0
    failures = []
    ran = 0
    for page in pages:
        n, f = run_page(page, source, os.path.abspath(a.build), a.python, os.path.abspath(a.work))
        ran += n
        failures += f
    for f in failures:
        print("FAILED " + f)
    print(f"{ran} commands/snippets run, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
