#!/usr/bin/env python3
"""Checks that the documentation matches the tree and the command (standard library only).

  check_docs.py links   --root SRC           relative links and repository paths in README.md and docs/ exist
  check_docs.py cli     --root SRC --cli EXE every option of every `depthtrack <command> --help` is in docs/user/cli.md
  check_docs.py config  --root SRC --cli EXE every key of `depthtrack config --dump` is in docs/user/configuration.md
  check_docs.py words   --root SRC           no history words (the project's numbered work items) in names or text
  check_docs.py ci      --root SRC           the README holds .ci/run's command byte for byte

Each failure names the file, the missing thing and where it came from; the exit code is 1.
"""
import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path


def fail(problems, what):
    for p in problems:
        print(f"FAIL: {p}")
    if problems:
        print(f"{len(problems)} problem(s) in {what}")
        return 1
    print(f"ok: {what}")
    return 0


def doc_files(root):
    files = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    return [f for f in files if f.is_file()]


def strip_code(text):
    """Markdown without fenced blocks and inline code spans (links inside them are not links)."""
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", text)


LINK = re.compile(r"\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
# A repository path written out in the prose or in code spans: its folder is one of the tree's.
REPO_PATH = re.compile(
    r"(?<![\w./-])((?:docs|scripts|src|include|cl|tests|bench|python|fuzz|cmake|shaders)/[\w./-]*\w\.(?:md|sh|py|cpp|hpp|h|cl|txt|cmake|json|png))(?![\w/-]|\.\w)")


def check_links(root):
    problems = []
    for f in doc_files(root):
        text = f.read_text(encoding="utf-8")
        rel = f.relative_to(root)
        for target in LINK.findall(strip_code(text)):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue  # a URL (http:, mailto:) or an anchor in the same file
            path = target.split("#", 1)[0]
            if not (f.parent / path).exists():
                problems.append(f"{rel}: link '{target}' points at nothing ({(f.parent / path).resolve()})")
        for path in REPO_PATH.findall(text):
            if not (root / path).exists():
                problems.append(f"{rel}: names '{path}', which is not in the repository")
    return fail(problems, "links and repository paths in README.md and docs/")


def run(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        sys.exit(f"FAIL: '{' '.join(['depthtrack', *args])}' exited {r.returncode}: {r.stderr.strip()}")
    return r.stdout


def help_of(cli, words):
    """Options and subcommands of `depthtrack WORDS --help` (CLI11's layout)."""
    text = run(cli, *words, "--help")
    options, subcommands, section = set(), [], None
    for line in text.splitlines():
        if re.match(r"^\S.*:\s*$", line):
            section = line.strip().rstrip(":").lower()
            continue
        if section == "subcommands":
            m = re.match(r"^\s+([a-z][\w-]*)\s", line + " ")
            if m:
                subcommands.append(m.group(1))
        elif section and section.startswith("options"):
            # Only the name column: "  -h,--help   Print..." or "  --mesh TEXT ... REQUIRED  Object mesh".
            m = re.match(r"^\s+(-[^\s]+)", line)
            if m:
                options.update(re.findall(r"--[A-Za-z0-9][\w-]*", m.group(1)))
    return options, subcommands


def cli_sections(md):
    """Text under each heading that names a command ("## `depthtrack track`"), keyed by 'track'."""
    sections, current = {}, None
    for line in md.splitlines():
        m = re.match(r"^#+\s+`depthtrack((?: [a-z][\w-]*)*)`", line)
        if m:
            current = m.group(1).strip()
            sections[current] = ""
            continue
        if current is not None:
            sections[current] += line + "\n"
    return sections


def check_cli(root, cli):
    doc = root / "docs/user/cli.md"
    sections = cli_sections(doc.read_text(encoding="utf-8"))
    problems, queue, seen = [], [[]], 0
    while queue:
        words = queue.pop(0)
        options, subcommands = help_of(cli, words)
        name = " ".join(words)
        shown = f"depthtrack {name}".strip()
        seen += 1
        if name not in sections:
            problems.append(f"docs/user/cli.md has no section '## `{shown}`' (a command of `depthtrack --help`)")
        else:
            for option in sorted(options):
                if not re.search(re.escape(option) + r"(?![\w-])", sections[name]):
                    problems.append(f"docs/user/cli.md, section `{shown}`: option {option} is not documented "
                                    f"(from `{shown} --help`)")
        queue += [words + [s] for s in subcommands]
    if seen < 2:
        problems.append("`depthtrack --help` listed no subcommands: the help's layout changed, fix help_of()")
    return fail(problems, f"options of {seen} commands in docs/user/cli.md")


def leaves(value, prefix=""):
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, f"{prefix}.{k}" if prefix else k)
    else:
        yield prefix


def check_config(root, cli):
    doc = (root / "docs/user/configuration.md").read_text(encoding="utf-8")
    keys = list(leaves(json.loads(run(cli, "config", "--dump"))))
    problems = [f"docs/user/configuration.md: key '{k}' is not documented (from `depthtrack config --dump`)"
                for k in keys if not re.search(r"`" + re.escape(k) + r"`", doc)]
    if not keys:
        problems.append("`depthtrack config --dump` printed no keys")
    return fail(problems, f"{len(keys)} configuration keys in docs/user/configuration.md")


# Work items of the project's past by number: history belongs to git and CHANGELOG.md.
HISTORY = re.compile(r"\b(iss" r"ue|rou" r"nd|sess" r"ion)s? ?#?[0-9]+", re.I)
TEXT_SUFFIXES = {".md", ".cpp", ".hpp", ".h", ".cl", ".c", ".py", ".sh", ".cmake", ".txt", ".in", ".vert",
                 ".frag", ".glsl", ".patch", ".dict", ""}
WORD_PLACES = ["README.md", "CMakeLists.txt", ".ci", "docs", "src", "include", "cl", "tests", "scripts", "bench",
               "python", "fuzz", "cmake", "shaders"]


def check_words(root):
    problems = []
    for place in WORD_PLACES:
        base = root / place
        files = [base] if base.is_file() else sorted(p for p in base.rglob("*") if p.is_file())
        for f in files:
            rel = f.relative_to(root)
            # Caches, hidden folders (.pytest_cache) and fuzz corpora (random bytes) are not the project's text.
            if "__pycache__" in rel.parts or "corpus" in rel.parts or any(
                    part.startswith(".") for part in rel.parts[1:]):
                continue
            if HISTORY.search(str(rel)):
                problems.append(f"{rel}: the file's name numbers a work item; name it by what it does")
            if f.suffix not in TEXT_SUFFIXES:
                continue
            try:
                lines = f.read_text(encoding="utf-8").splitlines()
            except UnicodeDecodeError:
                continue
            for n, line in enumerate(lines, 1):
                m = HISTORY.search(line)
                if m:
                    problems.append(f"{rel}:{n}: '{m.group(0)}' (say what holds now; history goes to git and CHANGELOG.md)")
    return fail(problems, "history words in names, comments and docs")


def check_ci(root):
    ci = [l for l in (root / ".ci/run").read_text().splitlines() if l.startswith("bash scripts/setup-debian.sh")]
    readme = (root / "README.md").read_text(encoding="utf-8").splitlines()
    problems = []
    if len(ci) != 1:
        problems.append(".ci/run: expected one line starting 'bash scripts/setup-debian.sh'")
    elif ci[0] not in readme:
        problems.append(f"README.md: no line is exactly .ci/run's command: {ci[0]}")
    return fail(problems, "README.md's test command against .ci/run")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("check", choices=["links", "cli", "config", "words", "ci"])
    parser.add_argument("--root", type=Path, required=True)
    parser.add_argument("--cli", help="the depthtrack executable (cli, config)")
    a = parser.parse_args()
    if a.check in ("cli", "config") and not (a.cli and os.access(a.cli, os.X_OK)):
        sys.exit(f"FAIL: --cli '{a.cli}' is not an executable")
    checks = {"links": lambda: check_links(a.root), "cli": lambda: check_cli(a.root, a.cli),
              "config": lambda: check_config(a.root, a.cli), "words": lambda: check_words(a.root),
              "ci": lambda: check_ci(a.root)}
    return checks[a.check]()


if __name__ == "__main__":
    sys.exit(main())
