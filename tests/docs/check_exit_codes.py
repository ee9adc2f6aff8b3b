#!/usr/bin/env python3
"""The exit codes the docs state against the README's table of exit codes.

  tests/docs/check_exit_codes.py [TOP]        # TOP: the tree's top folder (default: this repository)

README.md's "Exit codes" table is the one statement of what each code means. Every page under
docs/ that states a code ("refused with exit 2", "(exit 4)", "exits 3", "exit code 2") is read
clause by clause: the words a code is stated for (its clause up to it, from the last comma, asides
in parentheses left out) that speak of a cause the table gives a code to (a disk, memory, a
file that cannot be read or written: 4; a stop by a signal: 3; bad input: 2; a bug: 1) must state
that code, and every code stated must be one of the table's. The causes are matched by the words
below, and each cause's words are checked to be in the table's row of its code, so that the two
cannot drift apart either. A clause about the postprocess scripts (their own codes) or a launcher
(mpirun's, srun's) is not vibromap's and is skipped.

Prints one line per disagreement (file:line: the clause, the code stated, the code the table
gives) and exits 1 when there is one, 0 when there is none, 2 when the README has no table.
"""
import os
import re
import sys

# Causes, most specific first: the words that name each (lowercase), the code the table gives it,
# and a phrase of the table's row for that code that must be in the README.
CAUSES = (
    (4, ("disk", "cannot fit", "no space", "memory", "unwritable", "cannot be written", "could not be written",
         "file-size limit", "cannot be read", "could not be read", "damaged", "write that fails", "fails to write"),
     ("could not be read or written", "disk", "memory")),
    (3, ("sigint", "sigterm", "sigusr1", "signal", "stopped", "stops"), ("sigint", "sigterm", "sigusr1")),
    (1, ("a bug", "is always a bug", "unexpected error"), ("bug",)),
    (2, ("refused", "bad input", "invalid", "must be", "not a regular file", "no such key", "unknown"),
     ("bad input",)),
)
# Clauses about programs other than vibromap, whose codes the table does not give.
OTHERS = ("script", "postprocess", "mpirun", "srun", "launcher", "python", "summarize_map")
CODE = re.compile(r"\bexit(?:s|ed)?(?: with)?(?: (?:code|codes|status))? ([0-9]+)\b", re.IGNORECASE)


def readme_table(top):
    """{code: meaning} from README.md's "Exit codes" table."""
    table = {}
    with open(os.path.join(top, "README.md"), encoding="utf-8") as f:
        text = f.read()
    section = re.search(r"^## Exit codes\n(.*?)(?=^## )", text, re.MULTILINE | re.DOTALL)
    for m in re.finditer(r"^\|\s*([0-9]+)\s*\|\s*(.*?)\s*\|\s*$", section.group(1) if section else "", re.MULTILINE):
        table[int(m.group(1))] = m.group(2)
    return table


def check_causes(table):
    """Each cause's phrase must be in the table's row of its code."""
    problems = []
    for code, _, phrases in CAUSES:
        row = table.get(code, "").lower()
        for phrase in phrases:
            if phrase not in row:
                problems.append(f"README.md: the exit-code table's row {code} does not say '{phrase}' "
                                f"(tests/docs/check_exit_codes.py gives that cause code {code})")
    return problems


def clauses(text):
    """(offset, clause) for each clause of the text: split at sentence ends, semicolons, colons,
    list items and blank lines; a parenthesis stays with the clause it follows."""
    start = 0
    for m in re.finditer(r"(?:[.;:](?=\s)|\n\s*\n|\n\s*[-*|] |\n\s*[0-9]+\. )", text):
        yield start, text[start:m.end()]
        start = m.end()
    yield start, text[start:]


def phrase(before):
    """The words a code is stated for: the clause's text before it, its closed parentheses (asides)
    left out, from its last comma on."""
    while True:
        shorter = re.sub(r"\([^()]*\)", " ", before)
        if shorter == before:
            break
        before = shorter
    return before.rsplit(",", 1)[-1]


def check_page(path, rel, table):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"```.*?```", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.DOTALL)
    problems = []
    for offset, clause in clauses(text):
        for m in CODE.finditer(clause):
            code = int(m.group(1))
            line = text.count("\n", 0, offset + m.start()) + 1
            said = " ".join(clause.split())
            if any(word in said.lower() for word in OTHERS):
                continue
            if code not in table:
                problems.append(f"{rel}:{line}: exit {code} is not in README.md's table of exit codes: {said[:200]}")
                continue
            hit = cause(phrase(clause[:m.start()]).lower(), said.lower())
            if hit and hit[0] != code:
                problems.append(f"{rel}:{line}: states exit {code} for '{hit[1]}', which README.md's table "
                                f"gives exit {hit[0]} ({table[hit[0]]}): {said[:200]}")
    return problems


def cause(near, clause):
    """(code, word) of the cause the words `near` a code speak of, the most specific first; a
    resource (disk, memory) named anywhere in its clause outweighs a plain refusal near it (a
    trajectory too big for the disk "is refused ... (exit 4)"). None: no cause named."""
    for code, words, _ in CAUSES:
        word = next((w for w in words if w in near), None)
        if word:
            break
    else:
        code = None
    if code in (None, 2):
        resource = next((w for w in CAUSES[0][1] if w in clause), None)
        if resource:
            return CAUSES[0][0], resource
    return (code, word) if code is not None else None


def main(argv):
    top = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    table = readme_table(top)
    if not table:
        print("check_exit_codes: README.md has no '## Exit codes' table", file=sys.stderr)
        return 2
    problems = check_causes(table)
    docs = os.path.join(top, "docs")
    pages = sorted(n for n in os.listdir(docs) if n.endswith(".md") and n != "benchmarks.md")
    for name in pages:
        problems += check_page(os.path.join(docs, name), f"docs/{name}", table)
    for p in problems:
        print(p)
    print(f"check_exit_codes: {len(pages)} pages, {len(problems)} disagreements with README.md's exit codes")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
