#!/usr/bin/env python3
"""Checks docs/errata.md against itself and the tests (issue 39).

- The table under "## Counts" equals the tally of "## Sections of the manuals": per manual the
  sections listed, how many are honoured and how many decided; "open" is 0 and every section is
  one of the two.
- Every id a section names (LB-E8, CAN-D8..D13, ...) is the id of a row of this page.
- Every test named in backticks (`Suite.Name`, `Prefix/Suite.Name/*`, `Suite.*`) exists in tests/,
  and every trace file named exists in tests/data.

Usage: tools/check_errata.py [docs/errata.md]  (from the repository root; exit 1 with the reasons)
"""
import glob
import os
import re
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "errata.md")
text = open(path, encoding="utf-8").read()
problems = []


def section(title):
    m = re.search(r"^## " + re.escape(title) + r"\n(.*?)(?=^## |\Z)", text, re.S | re.M)
    if not m:
        problems.append(f"no section '## {title}'")
        return ""
    return m.group(1)


def rows(block):
    for line in block.splitlines():
        if line.startswith("|") and not line.startswith("| ---"):
            yield [c.strip() for c in line.strip().strip("|").split("|")]


# The counts table.
counts = {}
for cells in rows(section("Counts")):
    if cells[0] in ("manual",) or len(cells) != 5:
        continue
    counts[cells[0]] = [int(c) for c in cells[1:]]

# The section lists, one "### <manual>" each.
tally = {}
inventory = section("Sections of the manuals")
for m in re.finditer(r"^### (.+?)\n(.*?)(?=^### |\Z)", inventory, re.S | re.M):
    manual, block = m.group(1).strip(), m.group(2)
    n = h = d = 0
    for cells in rows(block):
        if cells[0] == "section":
            continue
        n += 1
        if cells[2] == "honoured":
            h += 1
        elif cells[2] == "decided":
            d += 1
        else:
            problems.append(f"{manual} {cells[0]}: status '{cells[2]}' is neither honoured nor decided (open)")
    tally[manual] = [n, h, d, n - h - d]
total = [sum(v[i] for v in tally.values()) for i in range(4)]
for manual, want in list(tally.items()) + [("all", total)]:
    have = counts.get(manual)
    if have != want:
        problems.append(f"Counts: {manual} reads {have}, the section list gives {want}")
for manual in counts:
    if manual != "all" and manual not in tally:
        problems.append(f"Counts: {manual} has no section list")
    if counts[manual][3] != 0:
        problems.append(f"Counts: {manual} has {counts[manual][3]} open sections")

# Ids: every row id of the page; every id a section names must be one.
ids = set()
for line in text.splitlines():
    m = re.match(r"\|\s*([A-Z][A-Z0-9]*(?:-[A-Z]+)?-?[A-Z]*\d+)\s*\|", line)
    if m:
        ids.add(m.group(1))
id_re = re.compile(r"\b((?:LB|CAN|VF|VFC|PCP|MC|DC|DFS1)-[A-Z]?\d+|PD\d+)(?:\.\.([A-Z]?)(\d+))?\b")
for m in id_re.finditer(inventory):
    first = m.group(1)
    if m.group(3):
        prefix, start = re.match(r"(.*?)(\d+)$", first).groups()
        names = [f"{prefix}{i}" for i in range(int(start), int(m.group(3)) + 1)]
    else:
        names = [first]
    for name in names:
        if name not in ids:
            problems.append(f"Sections of the manuals: {name} is no entry of this page")

# Tests and traces.
source = ""
for f in glob.glob(os.path.join(root, "tests", "**", "*.[ch]pp"), recursive=True):
    source += open(f, encoding="utf-8", errors="replace").read()
tests = set(re.findall(r"\b(?:TEST|TEST_F|TEST_P|TYPED_TEST)\(\s*(\w+)\s*,\s*(\w+)\s*\)", source))
suites = {s for s, _ in tests}
instances = set(re.findall(r"INSTANTIATE_TEST_SUITE_P\(\s*(\w+)\s*,\s*(\w+)", source))
for f in glob.glob(os.path.join(root, "tests", "**", "CMakeLists.txt"), recursive=True):
    tests |= set(re.findall(r"add_test\(NAME (\w+)\.(\w+)", open(f, encoding="utf-8").read()))
for m in re.finditer(r"`([^`\s]+)`", text):
    token = m.group(1)
    if token.endswith(".trace"):
        if not any(os.path.exists(os.path.join(root, *d, token)) for d in (("tests", "data"), ())):
            problems.append(f"trace {token} is not in tests/data")
        continue
    t = re.fullmatch(r"(?:(\w+)/)?(\w+)\.(\w+|\*)(/\*)?", token)
    if not t or token.endswith((".md", ".hpp", ".cpp", ".sh", ".py", ".toml")) or "_" in t.group(2)[:1]:
        continue
    prefix, suite, name = t.group(1), t.group(2), t.group(3)
    if not suite[0].isupper():
        continue
    if prefix and (prefix, suite) not in instances:
        problems.append(f"test {token}: no instantiation {prefix} of {suite}")
    elif name == "*" and suite not in suites:
        problems.append(f"test {token}: no suite {suite}")
    elif name != "*" and (suite, name) not in tests:
        problems.append(f"test {token} does not exist")

for p in problems:
    print(f"{path}: {p}", file=sys.stderr)
sys.exit(1 if problems else 0)
