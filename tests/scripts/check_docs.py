#!/usr/bin/env python3
"""The README and the guides of reports/docs/ hold together: every relative link resolves (the file,
and its #anchor as GitHub renders headings), every guide is linked from the README, and the README
stays a guide of at most 400 lines. Usage: check_docs.py REPO_ROOT"""
import os
import re
import sys


def slug(heading):
    h = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return h.replace(" ", "-")


def anchors(path):
    out, counts, fenced = set(), {}, False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fenced = not fenced
        if fenced:
            continue
        m = re.match(r"#+ (.*)", line)
        if m:
            s = slug(m.group(1))
            n = counts.get(s, 0)
            counts[s] = n + 1
            out.add(s if n == 0 else f"{s}-{n}")
    return out


def links(path):
    text = re.sub(r"```.*?```", "", open(path, encoding="utf-8").read(), flags=re.S)
    return [m.group(1) for m in re.finditer(r"\]\(([^)\s]+)\)", text)]


def main():
    root = sys.argv[1]
    readme = os.path.join(root, "README.md")
    docs = os.path.join(root, "reports", "docs")
    guides = sorted(os.path.normpath(os.path.join(docs, f)) for f in os.listdir(docs)
                    if f.endswith(".md"))
    errors = []
    for f in [readme] + guides:
        for t in links(f):
            if re.match(r"[a-z]+:", t):
                continue
            path, _, anchor = t.partition("#")
            target = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
            if not os.path.exists(target):
                errors.append(f"{os.path.relpath(f, root)}: links {t}, which does not exist")
            elif anchor and target.endswith(".md") and anchor not in anchors(target):
                errors.append(f"{os.path.relpath(f, root)}: links {t}, a heading it does not have")
    linked = {os.path.normpath(os.path.join(root, t.partition("#")[0])) for t in links(readme)}
    for g in guides:
        if g not in linked:
            errors.append(f"README.md does not link {os.path.relpath(g, root)}")
    n = sum(1 for _ in open(readme, encoding="utf-8"))
    if n > 400:
        errors.append(f"README.md is {n} lines: a guide of at most 400, the rest in reports/docs/")
    for e in errors:
        print("FAIL " + e)
    print(f"{len(guides)} guides, README {n} lines: {'ok' if not errors else 'broken'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
