#!/usr/bin/env python3
"""Runs clang-tidy on the project's files of a compile_commands.json, skipping those already found
clean with the same inputs (scripts/tidy.sh calls it; see there).

A file's inputs are: the file, every project header it includes (transitively, by scanning its
#include lines; a header under an #if counts too, so the set can only be too large), its compile
command with the tree's and build folder's paths taken out, .clang-tidy and clang-tidy's version.
Their SHA-256 names a marker in the cache folder, written when clang-tidy passes the file; a
marker present means the file passed with exactly these inputs, so it is not run again. System
headers are not hashed: a Debian upgrade of a library does not re-run the checks by itself
(delete the cache folder, or pass --no-cache, to run everything).

usage: tidy_files.py BUILD_DIR FILE_REGEX [--jobs N] [--batch N] [--cache DIR] [--no-cache]
"""

import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys
import time

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.MULTILINE)


def include_dirs(arguments, root, build_dir):
    """The -I / -isystem / -iquote folders of a command that lie in the tree or the build."""
    dirs = []
    for i, arg in enumerate(arguments):
        for flag in ("-I", "-isystem", "-iquote"):
            if arg == flag and i + 1 < len(arguments):
                path = arguments[i + 1]
            elif arg.startswith(flag) and len(arg) > len(flag):
                path = arg[len(flag):]
            else:
                continue
            path = os.path.abspath(path)
            if path.startswith(root) or path.startswith(build_dir):
                dirs.append(path)
    return dirs


class Inputs:
    """Hashes of files and of their project includes, each file read once."""

    def __init__(self, root, build_dir):
        self.root, self.build_dir = root, build_dir
        self.content = {}
        self.includes = {}

    def text(self, path):
        if path not in self.content:
            with open(path, "rb") as f:
                self.content[path] = f.read()
        return self.content[path]

    def project_includes(self, path, dirs):
        key = (path, tuple(dirs))
        if key in self.includes:
            return self.includes[key]
        found = []
        for name in INCLUDE.findall(self.text(path).decode("utf-8", "replace")):
            for folder in [os.path.dirname(path)] + dirs:
                candidate = os.path.normpath(os.path.join(folder, name))
                if os.path.isfile(candidate):
                    found.append(candidate)
                    break
        self.includes[key] = found
        return found

    def closure(self, path, dirs):
        seen, stack = set(), [path]
        while stack:
            current = stack.pop()
            if current in seen:
                continue
            seen.add(current)
            stack.extend(self.project_includes(current, dirs))
        return sorted(seen)

    def key(self, entry, common):
        arguments = entry.get("arguments") or shlex.split(entry["command"])
        source = os.path.abspath(os.path.join(entry["directory"], entry["file"]))
        dirs = include_dirs(arguments, self.root, self.build_dir)
        digest = hashlib.sha256(common)
        command = " ".join(arguments[1:]).replace(self.build_dir, "<build>").replace(self.root, "<src>")
        digest.update(command.encode())
        for path in self.closure(source, dirs):
            digest.update(os.path.relpath(path, self.root).encode() + b"\0")
            digest.update(hashlib.sha256(self.text(path)).digest())
        return digest.hexdigest()


def batch_header_filter(config_text):
    """The header filter of a batch run: the .clang-tidy HeaderFilterRegex, which must also match
    bench/ there, since a batch's sources are headers to clang-tidy."""
    match = re.search(r"^HeaderFilterRegex:\s*'/\((.*)\)/'\s*$", config_text, re.MULTILINE)
    if not match:
        sys.exit("tidy_files.py: .clang-tidy has no HeaderFilterRegex of the form '/(a|b|...)/'")
    return f"/({match.group(1)}|bench)/"


def unity_text(sources):
    """A translation unit that includes the given sources, in order."""
    return "".join(f'#include "{source}"\n' for source in sources)


def flags_of(entry):
    """A compile command's arguments without the compiler, the source and the output."""
    arguments = entry.get("arguments") or shlex.split(entry["command"])
    flags, skip = [], False
    for arg in arguments[1:]:
        if skip:
            skip = False
        elif arg == "-o":
            skip = True
        elif arg != "-c" and arg != entry["file"]:
            flags.append(arg)
    return flags


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build_dir")
    parser.add_argument("file_regex")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--cache", default=os.path.expanduser("~/.cache/aggpack/tidy"))
    parser.add_argument("--no-cache", action="store_true")
    parser.add_argument("--tidy", default="clang-tidy")
    parser.add_argument("--clang", default="clang++-14",
                        help="the compiler that checks which files compile together")
    parser.add_argument("--batch", type=int, default=12,
                        help="files per clang-tidy run (1: one run per file)")
    args = parser.parse_args()

    root = os.getcwd()
    build_dir = os.path.abspath(args.build_dir)
    with open(os.path.join(build_dir, "compile_commands.json")) as f:
        entries = json.load(f)
    pattern = re.compile("^" + re.escape(root) + "/" + args.file_regex)
    chosen = {}
    for entry in entries:
        source = os.path.abspath(os.path.join(entry["directory"], entry["file"]))
        if pattern.match(source) and source not in chosen:
            chosen[source] = entry
    version = subprocess.run([args.tidy, "--version"], capture_output=True, text=True).stdout
    with open(os.path.join(root, ".clang-tidy"), "rb") as f:
        config = f.read()
    common = version.encode() + b"\0" + config
    header_filter = batch_header_filter(config.decode("utf-8"))
    inputs = Inputs(root, build_dir)
    keys = {source: inputs.key(entry, common) for source, entry in chosen.items()}

    os.makedirs(args.cache, exist_ok=True)
    # Markers of runs more than 60 days old go: the folder stays small.
    now = time.time()
    for name in os.listdir(args.cache):
        marker = os.path.join(args.cache, name)
        if now - os.path.getmtime(marker) > 60 * 86400:
            os.remove(marker)
    todo = [s for s in sorted(chosen)
            if args.no_cache or not os.path.exists(os.path.join(args.cache, keys[s]))]

    def run(source):
        result = subprocess.run(
            [args.tidy, "-p", build_dir, "-quiet", "--extra-arg=-Wno-unknown-warning-option",
             source], capture_output=True, text=True)
        return source, result.returncode, result.stdout + result.stderr

    unity_dir = os.path.join(build_dir, "tidy-unity")
    os.makedirs(unity_dir, exist_ok=True)

    def compatible(batch):
        """Splits a batch into runs of files that compile together in one unity file (checked
        with clang -fsyntax-only, much cheaper than clang-tidy): a file with an error there (a
        name another file of the batch also defines at file scope) moves to a later run."""
        runs = []
        while batch:
            current, later = list(batch), []
            while len(current) > 1:
                entry = chosen[current[0]]
                errors = set()
                result = subprocess.run(
                    [args.clang, "-fsyntax-only", "-w", "-ferror-limit=0", "-x", "c++", "-"]
                    + flags_of(entry), input=unity_text(current),
                    cwd=entry["directory"], capture_output=True, text=True)
                if result.returncode == 0:
                    break
                for line in result.stderr.splitlines():
                    match = re.match(r"^(/[^:]+):\d+:\d+: (?:fatal )?error:", line)
                    if match and match.group(1) in current:
                        errors.add(match.group(1))
                if not errors or errors.issuperset(current):
                    # An error we cannot place on one of the batch's files: the first file goes
                    # alone (checked by itself), the rest to a later run.
                    later, current = current[1:] + later, current[:1]
                    break
                later = [s for s in current if s in errors] + later
                current = [s for s in current if s not in errors]
            runs.append(current)
            batch = sorted(later)
        return runs

    def run_batch(batch):
        """One clang-tidy run over a unity file that includes the batch's sources (same compile
        command): the system headers every file includes (Eigen alone is ~5 s of clang-tidy's CPU
        per file) are parsed and matched once per batch instead of once per file. Files that do
        not compile together go to other batches (compatible); a batch with a finding is checked
        again file by file, so findings are reported exactly as a per-file run reports them."""
        outcome = []
        for part in compatible(batch):
            if len(part) == 1:
                outcome.append((run(part[0]), False))
                continue
            entry = chosen[part[0]]
            unity = os.path.join(unity_dir, hashlib.sha256("\0".join(part).encode()).hexdigest()
                                 [:16] + ".cpp")
            with open(unity, "w") as f:
                f.write(unity_text(part))
            try:
                result = subprocess.run(
                    [args.tidy, "-quiet", "--extra-arg=-Wno-unknown-warning-option",
                     f"--header-filter={header_filter}", unity, "--"] + flags_of(entry),
                    cwd=entry["directory"], capture_output=True, text=True)
            finally:
                os.remove(unity)
            if result.returncode == 0:
                outcome.extend(((source, 0, ""), True) for source in part)
            else:
                outcome.extend((run(source), False) for source in part)
        return outcome

    # Batches of files with the same compile command (one target's files, in path order).
    groups = {}
    for source in todo:
        groups.setdefault(tuple(flags_of(chosen[source])), []).append(source)
    size = max(1, args.batch)
    batches = [files[i:i + size] for files in groups.values() for i in range(0, len(files), size)]

    findings, failed = set(), []
    batched = 0
    with open(os.path.join(build_dir, "tidy.log"), "w") as log, \
            concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for results in pool.map(run_batch, batches):
            for (source, status, output), whole in results:
                batched += 1 if whole else 0
                log.write(f"== {os.path.relpath(source, root)} (exit {status})\n{output}\n")
                clean = re.sub(r"\x1b\[[0-9;]*m", "", output)
                findings.update(line for line in clean.splitlines()
                                if "warning:" in line or "error:" in line)
                if status == 0:
                    open(os.path.join(args.cache, keys[source]), "w").close()
                else:
                    failed.append(source)
    for line in sorted(findings):
        print(line)
    summary = (f"{len(chosen)} files: {len(todo)} checked ({batched} in clean batches), "
               f"{len(chosen) - len(todo)} unchanged since a clean run")
    if failed:
        print(f"tidy: clang-tidy found problems in {len(failed)} of {summary} "
              f"(full log: {os.path.relpath(build_dir, root)}/tidy.log)")
        return 1
    print(f"tidy: clean ({summary})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
