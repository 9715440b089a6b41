#!/usr/bin/env python3
"""Rewrites citations of the manuals by their reference-set number to their short names
(docs/errata.md, "The manuals"; issue 39): "seed 000, 6.2.2" -> "LUSTBUS manual 6.2.2",
"seed 001 5.3.4" -> "INTERBUS manual 5.3.4", "seed 003's table" -> "the CANLust manual's table",
and in citations without the word "seed" ("| 001, 5.3.4, last row |", "001 4.1.3.3 vs 000
2.3.1", "004, note 2") the number alone. Inline code and fenced blocks are left alone, and so is
a number that is no citation (a count such as "60 000", "000 is the LUSTBUS manual").

Usage: tools/cite_manuals.py FILE...   (rewrites the files in place; prints the count per file)
"""
import re
import sys

SHORT = {"000": "LUSTBUS manual", "001": "INTERBUS manual", "003": "CANLust manual", "004": "DFS-1 manual"}
NUM = r"(000|001|003|004)"
SECTION = r"\d+(?:\.\d+)*(?:\.x)?"
# What may follow a bare number for it to be a citation: a section, or a word a citation uses.
BARE_NEXT = (r"(?:,? " + SECTION + r"\b|:| says|,? (?:note|notes|parameter|parameters|command|commands|status|"
             r"silent|no |definitions|header|response|error|communications|section|sections|table|"
             r"p\.|vs|and the notes)|\))")


def cite(m):
    seed, num, rest = m.group(1), m.group(2), m.group(3) or ""
    name = SHORT[num]
    if re.match(r",? " + SECTION + r"\b", rest):
        return name + rest.lstrip(",")
    if rest.startswith("'s"):
        return ("The " if seed[0] == "S" else "the ") + name + rest
    after = m.string[m.end():]
    if (seed and not rest.startswith(",") and not after.startswith((",", ")"))) or after.startswith(" says"):
        return ("The " if seed[:1] == "S" else "the ") + name + rest
    return name + rest


def rewrite(line):
    out, pos = [], 0
    # Leave inline code alone.
    for m in re.finditer(r"`[^`]*`", line):
        out.append(sweep(line[pos:m.start()]))
        out.append(m.group(0))
        pos = m.end()
    out.append(sweep(line[pos:]))
    return "".join(out)


def sweep(text):
    text = re.sub(r"\b[Ss]eeds 000 and 001\b", "the LUSTBUS and INTERBUS manuals", text)
    text = re.sub(r"\b([Ss]eeds?) " + NUM + r"((?:'s|,? " + SECTION + r"\b)?)", cite, text)
    return re.sub(r"(?<![\w.\-])(?<!\d )()" + NUM + r"(?=" + BARE_NEXT + r")((?:,? " + SECTION + r"\b)?)",
                  cite, text)


def main(paths):
    for path in paths:
        lines = open(path, encoding="utf-8").read().split("\n")
        fenced, changed = False, 0
        for i, line in enumerate(lines):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if fenced:
                continue
            new = rewrite(line)
            if new != line:
                lines[i] = new
                changed += 1
        if changed:
            open(path, "w", encoding="utf-8").write("\n".join(lines))
        print(f"{path}: {changed} lines")


if __name__ == "__main__":
    main(sys.argv[1:])
