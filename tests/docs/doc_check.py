#!/usr/bin/env python3
"""Checks that README.md and docs/*.md stay true (docs/development.md, "Documentation that stays
true"):

  commands    every `ligsim` command line of a ```sh block passes the dry run
              (LIGSIM_CHECK_ONLY=1) and then runs, as written or as its block's marker says
  help-pages  every subcommand's --help ends with "Guide: docs/<page>.md", an existing page
  links       every relative link names an existing file, and its #anchor one of its headings

Exits 1 naming each failure (page and line)."""

import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

MARKER = re.compile(r"<!--\s*doc-test:\s*(check-only|short)\b(.*?)-->")


def pages_in_order(source):
    """README.md, then the guide's pages in the order of docs/README.md, then any others, then
    the benchmark records of docs/validation/."""
    docs = os.path.join(source, "docs")
    order = ["README.md", "docs/README.md"]
    with open(os.path.join(docs, "README.md"), encoding="utf-8") as index:
        for target in re.findall(r"\]\(([a-z0-9_-]+\.md)\)", index.read()):
            if "docs/" + target not in order:
                order.append("docs/" + target)
    for name in sorted(os.listdir(docs)):
        if name.endswith(".md") and "docs/" + name not in order:
            order.append("docs/" + name)
    records = os.path.join(docs, "validation")  # benchmark records (tests/bench/record.sh)
    if os.path.isdir(records):
        order += ["docs/validation/" + name for name in sorted(os.listdir(records))
                  if name.endswith(".md")]
    return order


def code_blocks(text):
    """(info string, marker or None, first line number, lines) of every fenced block."""
    blocks = []
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        fence = re.match(r"^(```+)\s*(\S*)", lines[i])
        if not fence:
            i += 1
            continue
        marker = None
        j = i - 1
        while j >= 0 and not lines[j].strip():
            j -= 1
        if j >= 0:
            found = MARKER.search(lines[j])
            if found:
                marker = (found.group(1), found.group(2).strip())
        body = []
        start = i + 1
        i += 1
        while i < len(lines) and not lines[i].startswith(fence.group(1)):
            body.append(lines[i])
            i += 1
        blocks.append((fence.group(2), marker, start + 1, body))
        i += 1
    return blocks


def commands_of(body, first_line):
    """(line number, argv) of every ligsim command: lines joined at trailing backslashes, split
    at &&, whose first word is ligsim or ends in /ligsim."""
    found = []
    logical, number = "", None
    for offset, line in enumerate(body):
        if number is None:
            number = first_line + offset
        if line.rstrip().endswith("\\"):
            logical += line.rstrip()[:-1] + " "
            continue
        logical += line
        words = shlex.split(logical, comments=True)
        piece = []
        for word in words + ["&&"]:
            if word in ("&&", ";", "||"):
                if piece and (piece[0] == "ligsim" or piece[0].endswith("/ligsim")):
                    found.append((number, piece[1:]))
                piece = []
            else:
                piece.append(word)
        logical, number = "", None
    return found


def job_of(arguments):
    """The words before the first option (the subcommand path, then positionals)."""
    words = [word for word in arguments if word not in ("-q", "--quiet")]
    path = []
    for word in words:
        if word.startswith("-"):
            break
        path.append(word)
    return path


def option_groups(words):
    """[(option, [values])] of a word list (values: the words up to the next --option)."""
    groups = []
    for word in words:
        if word.startswith("--"):
            groups.append((word, []))
        elif groups:
            groups[-1][1].append(word)
        else:
            raise ValueError("a short variant's options must start with --: " + " ".join(words))
    return groups


def shortened(arguments, marker_text):
    """The arguments with the marker's options for this job: "JOB: --opt v; JOB: ..."."""
    job = job_of(arguments)
    result = list(arguments)
    for part in marker_text.split(";"):
        if not part.strip():
            continue
        name, _, options = part.partition(":")
        if job[: len(name.split())] != name.split():
            continue
        for option, values in option_groups(shlex.split(options)):
            if option in result:
                at = result.index(option) + 1
                end = at
                while end < len(result) and not result[end].startswith("--"):
                    end += 1
                result[at:end] = values
            else:
                result += [option] + values
    return result


def check_commands(args):
    work = args.work
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(os.path.join(work, "bin"))
    for name in ("data", "tests", "workflow"):
        os.symlink(os.path.join(args.source, name), os.path.join(work, name))
    os.symlink(args.build, os.path.join(work, "build"))
    os.symlink(args.ligsim, os.path.join(work, "bin", "ligsim"))
    environment = dict(os.environ, PATH=os.path.join(work, "bin") + os.pathsep + os.environ["PATH"])
    check_environment = dict(environment, LIGSIM_CHECK_ONLY="1")

    failures, ran, total_start = [], set(), time.time()
    for page in pages_in_order(args.source):
        with open(os.path.join(args.source, page), encoding="utf-8") as file:
            text = file.read()
        for info, marker, first_line, body in code_blocks(text):
            if info != "sh":
                continue
            for number, arguments in commands_of(body, first_line):
                where = "%s:%d" % (page, number)
                line = "ligsim " + " ".join(arguments)
                checked = subprocess.run([args.ligsim] + arguments, cwd=work, env=check_environment,
                                         capture_output=True, text=True)
                if checked.returncode != 0:
                    failures.append("%s: `%s` fails the dry run (exit %d):\n%s" % (
                        where, line, checked.returncode, checked.stderr.strip()[-2000:]))
                    print("FAIL (dry run) %s: %s" % (where, line), flush=True)
                    continue
                if marker and marker[0] == "check-only":
                    print("dry run  %s: %s" % (where, line), flush=True)
                    continue
                real = shortened(arguments, marker[1]) if marker else arguments
                if tuple(real) in ran:
                    print("done     %s: %s (ran above)" % (where, line), flush=True)
                    continue
                start = time.time()
                done = subprocess.run([args.ligsim, "-q"] + real, cwd=work, env=environment,
                                      capture_output=True, text=True)
                seconds = time.time() - start
                if done.returncode != 0:
                    failures.append("%s: `ligsim %s` fails (exit %d):\n%s" % (
                        where, " ".join(real), done.returncode, done.stderr.strip()[-2000:]))
                    print("FAIL     %s: ligsim %s" % (where, " ".join(real)), flush=True)
                    continue
                ran.add(tuple(real))
                print("ran      %s: ligsim %s (%.1f s)" % (where, " ".join(real), seconds), flush=True)
    print("%.0f s in all" % (time.time() - total_start))
    return failures


def check_help_pages(args):
    failures = []

    def visit(path):
        shown = subprocess.run([args.ligsim] + path + ["--help"], capture_output=True, text=True)
        lines = [line for line in shown.stdout.split("\n") if line.strip()]
        name = "ligsim " + " ".join(path) if path else "ligsim"
        last = lines[-1].strip() if lines else ""
        found = re.fullmatch(r"Guide: (docs/[A-Za-z0-9_-]+\.md)", last)
        if not found:
            failures.append("`%s --help` ends with %r, not with a guide page" % (name, last))
        elif not os.path.isfile(os.path.join(args.source, found.group(1))):
            failures.append("`%s --help` names %s, which does not exist" % (name, found.group(1)))
        listing = shown.stdout.split("Subcommands:\n", 1)
        if len(listing) == 2:
            for line in listing[1].split("\n"):
                sub = re.match(r"^  (\S+)", line)
                if not sub:
                    break
                visit(path + [sub.group(1)])

    visit([])
    return failures


def slug(heading):
    """GitHub's anchor of a heading."""
    text = re.sub(r"`", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(file):
    with open(file, encoding="utf-8") as handle:
        text = handle.read()
    seen, result = {}, set()
    in_code = False
    for line in text.split("\n"):
        if line.startswith("```"):
            in_code = not in_code
            continue
        heading = re.match(r"^#{1,6} (.*)", line)
        if heading and not in_code:
            base = slug(heading.group(1))
            count = seen.get(base, 0)
            seen[base] = count + 1
            result.add(base if count == 0 else "%s-%d" % (base, count))
    return result


def check_links(args):
    failures = []
    for page in pages_in_order(args.source):
        path = os.path.join(args.source, page)
        with open(path, encoding="utf-8") as handle:
            lines = handle.read().split("\n")
        in_code = False
        for number, line in enumerate(lines, 1):
            if line.startswith("```"):
                in_code = not in_code
                continue
            if in_code:
                continue
            prose = re.sub(r"`[^`]*`", "", line)
            for target in re.findall(r"\]\(([^)\s]+)\)", prose):
                if re.match(r"^[a-z]+:", target):
                    continue
                file_part, _, anchor = target.partition("#")
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) \
                    if file_part else path
                where = "%s:%d" % (page, number)
                if not os.path.exists(resolved):
                    failures.append("%s: link to %s: no such file" % (where, target))
                elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                    failures.append("%s: link to %s: no heading with that anchor" % (where, target))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("check", choices=["commands", "help-pages", "links"])
    parser.add_argument("--source", required=True)
    parser.add_argument("--ligsim")
    parser.add_argument("--build")
    parser.add_argument("--work")
    args = parser.parse_args()
    if args.check == "commands":
        failures = check_commands(args)
    elif args.check == "help-pages":
        failures = check_help_pages(args)
    else:
        failures = check_links(args)
    for failure in failures:
        print("FAILED: " + failure)
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
