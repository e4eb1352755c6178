#!/usr/bin/env python3
"""Every ```sh and ```python block of README.md and docs/*.md runs as written (issue 40).

Each block runs in a scratch folder that looks like a checkout to it: json-cases/ copied, build/bin/drillwave and
build/python linked to the build under test (and build/bin on PATH), ../shared linked to the workplace's shared
folder when there is one. The blocks of one document run in order in the same folder, so a command may read what an
earlier one wrote (fit reads out/default/trajectory.csv). A shell block is run command by command (continued lines
joined); a Python block as a whole, as a script file, with PYTHONPATH=build/python as the README says.

How much runs (--run), and what is not run and why, is printed for every step:
- --run none (ctest label fast, a second): nothing runs; every step is checked: a drillwave command's options are
  ones its subcommand's --help lists, the input files it names exist (those under out/ are an earlier step's
  outputs) and its case validates; a Python block compiles and its keywords are ones the function's signature names.
- --run cheap (label slow, under a minute): every step runs but the costly ones (diagnose: minutes per recording,
  and what reads diagnose's output), which are checked as above.
- --run all (label long): every step runs.
Skipped always: a block the document marks on the line before it with `<!-- not run: REASON -->` (one that can run
nowhere as written, e.g. a cluster's address), the install-and-build scripts and `cmake --install` (they change the machine; CI runs scripts/test.sh
itself and tests/package checks the install), the estimator's scoring script; and whatever needs ../shared, the
Python module or NumPy when it is absent.

Usage: readme_blocks.py --source DIR --binary FILE [--python-dir DIR] [--shared DIR] [--run none|cheap|all]
Exit 0: every step passed; 1: a step failed (its output is printed).
"""
import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

FENCE = re.compile(r"^```(\S*)\s*$")
# Written on the line before a block that cannot run anywhere as written (a cluster's address, say), with the reason.
NOT_RUN = re.compile(r"^<!-- not run: (.+) -->\s*$")
RUN_LANGUAGES = ("sh", "python")

# (pattern on a step's text, why it is not run)
SKIPPED = [
    (re.compile(r"^\s*bash scripts/(run-default|test)\.sh"),
     "installs system packages and builds the project; CI (.ci/run) runs scripts/test.sh itself"),
    (re.compile(r"^\s*cmake --install"), "installs into /opt; tests/package checks the installed package"),
    (re.compile(r"scripts/score_estimates\.py"),
     "scores the estimator on 48 recordings and the rig (many minutes); the scoring script's own table"),
]
# (pattern, why it is costly): run only with --costly run.
COSTLY = [
    (re.compile(r"\bdiagnose\b"), "diagnose fits models for minutes per recording"),
    (re.compile(r"\bOUT/"), "reads the output of the rig's diagnose"),
    (re.compile(r"\bcalibrate\b"), "samples a posterior: thousands of model runs"),
    (re.compile(r"posterior_samples\.csv"), "reads the output of calibrate"),
]


class Step:
    def __init__(self, document, line, language, text, not_run=None):
        self.document, self.line, self.language, self.text = document, line, language, text
        self.not_run = not_run  # the document's own reason not to run it, or None

    def where(self):
        return f"{self.document}:{self.line}"


def fenced_blocks(path):
    """(line of the opening fence, language, text, reason not to run it or None) of every fenced block."""
    blocks, language, start, lines, previous, not_run = [], None, 0, [], "", None
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = FENCE.match(line.rstrip("\n"))
            if language is None and m:
                marker = NOT_RUN.match(previous)
                language, start, lines, not_run = m.group(1), number, [], marker.group(1) if marker else None
            elif language is not None and line.strip() == "```":
                blocks.append((start, language, "".join(lines), not_run))
                language = None
            elif language is not None:
                lines.append(line)
            if line.strip():
                previous = line.strip()
    return blocks


def shell_commands(start, text):
    """(line, command) of a shell block: continued lines joined, blank and comment-only lines left out."""
    commands, current, first = [], "", 0
    for offset, line in enumerate(text.splitlines(), 1):
        if not current:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            first = start + offset
        if line.rstrip().endswith("\\"):
            current += line.rstrip()[:-1] + " "
            continue
        commands.append((first, current + line))
        current = ""
    if current:
        commands.append((first, current))
    return commands


def steps_of(source, document):
    steps = []
    for start, language, text, not_run in fenced_blocks(os.path.join(source, document)):
        if language == "sh":
            steps += [Step(document, line, "sh", command, not_run) for line, command in shell_commands(start, text)]
        elif language == "python":
            steps.append(Step(document, start + 1, "python", text, not_run))
    return steps


def documents(source):
    docs = ["README.md"]
    docs += sorted(os.path.join("docs", f) for f in os.listdir(os.path.join(source, "docs")) if f.endswith(".md"))
    return docs


def make_scratch(args, root):
    """The folder the blocks run in, laid out as a checkout beside ../shared."""
    work = os.path.join(root, "checkout")
    os.makedirs(os.path.join(work, "build", "bin"))
    shutil.copytree(os.path.join(args.source, "json-cases"), os.path.join(work, "json-cases"))
    os.symlink(os.path.abspath(args.binary), os.path.join(work, "build", "bin", "drillwave"))
    if args.python_dir:
        os.symlink(os.path.abspath(args.python_dir), os.path.join(work, "build", "python"))
    if args.shared and os.path.isdir(args.shared):
        os.symlink(os.path.abspath(args.shared), os.path.join(root, "shared"))
    return work


def environment(work):
    env = dict(os.environ)
    env["PATH"] = os.path.join(work, "build", "bin") + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = "build/python"  # relative, as the README has it
    env["DRILLWAVE_PROGRESS_S"] = "0"
    return env


def module_built(folder):
    return bool(folder) and os.path.isdir(folder) and any(f.startswith("drillwave.") for f in os.listdir(folder))


def reason_to_skip(step, args):
    if step.not_run:
        return f"the document says: {step.not_run}"
    for pattern, why in SKIPPED:
        if pattern.search(step.text):
            return why
    if "../shared" in step.text and not (args.shared and os.path.isdir(args.shared)):
        return f"needs ../shared (the workplace's recordings), absent at {args.shared}"
    if step.language == "python" and not module_built(args.python_dir):
        return f"the Python module is not built (at {args.python_dir}; DRILLWAVE_PYTHON=OFF?)"
    if step.language == "python":
        try:
            import numpy  # noqa: F401  (the module returns NumPy arrays)
        except ImportError:
            return "NumPy is missing (Debian: python3-numpy)"
    return None


def not_run(step, how_much):
    """Why a step is only checked, not run; None to run it."""
    if how_much == "none":
        return "--run none"
    if how_much == "cheap":
        for pattern, why in COSTLY:
            if pattern.search(step.text):
                return why + "; --run all runs it"
    return None


def run(command, work, env, timeout):
    """(exit code, output, seconds); on a timeout the step's whole process group is killed (worker processes too)
    and subprocess.TimeoutExpired raised."""
    started = time.monotonic()
    with subprocess.Popen(command, cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          start_new_session=True) as p:
        try:
            output, _ = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
            raise
    return p.returncode, output, time.monotonic() - started


def run_step(step, work, env, timeout):
    if step.language == "sh":
        return run(["bash", "-e", "-o", "pipefail", "-c", step.text], work, env, timeout)
    # From a file, as a user's script (worker processes that import the main script need one).
    script = os.path.join(work, f"readme_block_{step.line}.py")
    with open(script, "w", encoding="utf-8") as f:
        f.write(step.text)
    return run([sys.executable, script], work, env, timeout)


def output_folders(step):
    """The folders a shell step writes (-o, --out)."""
    words = shlex.split(step.text, comments=True) if step.language == "sh" else []
    return {after for before, after in zip(words, words[1:]) if before in ("-o", "--out")}


def check_shell_without_running(step, work, env, written):
    """Problems of a drillwave command found without running it: options its subcommand does not list, input
    files that do not exist (unless an earlier step writes them: `written` holds its output folders), a case that
    does not validate."""
    words = shlex.split(step.text, comments=True)
    if "|" in words:  # a pipe into drillwave: its source is checked by running it only
        words = words[words.index("|") + 1:]
    if not words or not words[0].endswith("drillwave"):
        return ["not a drillwave command: cannot check it without running it"]
    subcommand = words[1] if len(words) > 1 and not words[1].startswith("-") else ""
    code, help_text, _ = run([words[0]] + ([subcommand] if subcommand else []) + ["--help"], work, env, 60)
    problems = [] if code == 0 else [f"{subcommand} --help exits {code}"]
    help_text += run([words[0], "--help"], work, env, 60)[1]  # the tool's own options (--max-samples) go anywhere
    listed = set(re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", help_text))
    for word in words[2:]:
        option = word.split("=", 1)[0]
        if word.startswith("[") and word.endswith("]"):
            problems.append(f"{word}: usage notation for an optional part, not a word the shell passes on")
        elif option.startswith("-") and option != "-" and option not in listed:  # "-": standard input
            problems.append(f"{subcommand} --help does not list {option}")
        elif re.search(r"\.(json|csv)$", word) and not any(word.startswith(f + "/") for f in written) and \
                not os.path.exists(os.path.join(work, word)):
            problems.append(f"no file {word}")
    case = words[2] if len(words) > 2 and words[2].endswith(".json") else None
    if case and os.path.exists(os.path.join(work, case)):
        code, output, _ = run([words[0], "validate", case], work, env, 60)
        if code != 0:
            problems.append(f"validate {case} exits {code}: {output.strip()}")
    return problems


def drillwave_calls(text):
    """(function, argument text) of every drillwave.f(...) call: up to its matching parenthesis."""
    calls = []
    for m in re.finditer(r"drillwave\.(\w+)\(", text):
        depth, end = 1, m.end()
        while end < len(text) and depth:
            depth += {"(": 1, "[": 1, "{": 1, ")": -1, "]": -1, "}": -1}.get(text[end], 0)
            end += 1
        calls.append((m.group(1), text[m.end():end - 1]))
    return calls


def check_python_without_running(step, work, env, written):
    """Problems of a Python block found without running it: a syntax error, a keyword a drillwave function's
    signature does not name, a file that does not exist."""
    try:
        compile(step.text, step.where(), "exec")
    except SyntaxError as e:
        return [f"syntax error: {e}"]
    calls = drillwave_calls(step.text)
    probe = "import drillwave, sys\nfor name, kws in %r:\n" \
            "    doc = getattr(drillwave, name).__doc__ or ''\n" \
            "    for kw in kws:\n" \
            "        if kw + ': ' not in doc and kw + '=' not in doc: print(f'{name}() takes no keyword {kw}')\n"
    without_strings = [(name, re.sub(r"\"[^\"]*\"|'[^']*'", '""', arguments)) for name, arguments in calls]
    wanted = [(name, re.findall(r"\b(\w+)=", arguments)) for name, arguments in without_strings]
    code, output, _ = run([sys.executable, "-c", probe % wanted], work, env, 60)
    problems = [line for line in output.splitlines() if line.strip()]
    if code != 0:
        problems.append(f"the probe exits {code}")
    for name in re.findall(r"\"([^\"]+\.(?:json|csv))\"", step.text):
        if not os.path.exists(os.path.join(work, name)):
            problems.append(f"no file {name}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--binary", required=True)
    parser.add_argument("--python-dir")
    parser.add_argument("--shared")
    parser.add_argument("--run", choices=["none", "cheap", "all"], default="cheap")
    parser.add_argument("--timeout", type=float, default=600, help="seconds per step")
    args = parser.parse_args()
    if args.shared is None:
        args.shared = os.path.join(args.source, "..", "shared")

    failures, counts = 0, {"ran": 0, "checked": 0, "skipped": 0}
    for document in documents(args.source):
        steps = steps_of(args.source, document)
        if not steps:
            print(f"{document}: no sh or python blocks")
            continue
        with tempfile.TemporaryDirectory(prefix="drillwave-readme-") as root:
            work = make_scratch(args, root)
            env = environment(work)
            written = set()  # output folders of the steps so far
            for step in steps:
                written |= output_folders(step)
                summary = step.text.strip().splitlines()[0][:100]
                skip = reason_to_skip(step, args)
                if skip:
                    counts["skipped"] += 1
                    print(f"SKIPPED {step.where()} {summary}\n        {skip}")
                    continue
                why_not_run = not_run(step, args.run)
                if why_not_run:
                    counts["checked"] += 1
                    check = check_shell_without_running if step.language == "sh" else check_python_without_running
                    problems = check(step, work, env, written)
                    print(f"{'FAILED' if problems else 'CHECKED'} {step.where()} {summary}\n"
                          f"        not run ({why_not_run}): options, files and case checked")
                    for p in problems:
                        print(f"        {p}")
                    failures += bool(problems)
                    continue
                counts["ran"] += 1
                try:
                    code, output, seconds = run_step(step, work, env, args.timeout)
                except subprocess.TimeoutExpired:
                    code, output, seconds = "timeout", "", args.timeout
                print(f"{'RAN' if code == 0 else 'FAILED'} {step.where()} {summary} ({seconds:.1f} s)")
                if code != 0:
                    failures += 1
                    print(f"        exit {code}; as written:\n{step.text}\n        output:\n{output[-4000:]}")
    print(f"{counts['ran']} run, {counts['checked']} checked without running, {counts['skipped']} skipped, "
          f"{failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
