#!/usr/bin/env python3
"""Checks that a `meshreuse report` folder is well-formed (CI runs it on reproduce.sh --quick):
run.json parses and names the build; every table the manifest lists has CSV (rectangular, with a
header), Markdown (a header rule, one line per CSV row) and LaTeX (booktabs, one line per CSV row);
every data file it lists exists; every figure it lists exists as a valid PNG and PDF and is shown
in the README; every link in the README resolves. What a report holds comes from its
manifest.json (written from reports/report_list.h): this checker keeps no list of its own.

  check_report.py DIR [FIGURE ...]   (FIGUREs: figure names that must be present)
"""
import csv
import json
import os
import re
import sys

def fail(msg):
    raise SystemExit(f"check_report: {msg}")


def check_png(path):
    with open(path, "rb") as f:
        b = f.read()
    if not b.startswith(b"\x89PNG\r\n\x1a\n") or b[-8:-4] != b"IEND":
        fail(f"{path}: not a complete PNG")


def check_pdf(path):
    with open(path, "rb") as f:
        b = f.read()
    if not b.startswith(b"%PDF-") or b"%%EOF" not in b[-1024:]:
        fail(f"{path}: not a complete PDF")


def check_table(d, name):
    base = os.path.join(d, "tables", name)
    with open(base + ".csv", newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        fail(f"{base}.csv: no rows")
    if any(len(r) != len(rows[0]) for r in rows):
        fail(f"{base}.csv: rows of different lengths")
    md = open(base + ".md").read().splitlines()
    if len(md) != len(rows) + 1 or not re.match(r"^\|(-+:?\|)+$", md[1]):
        fail(f"{base}.md: {len(md)} lines for {len(rows)} CSV rows, or no header rule")
    tex = open(base + ".tex").read()
    for k in ("\\begin{tabular}", "\\toprule", "\\midrule", "\\bottomrule", "\\end{tabular}",
              "\\caption{", "\\label{tab:" + name + "}"):
        if k not in tex:
            fail(f"{base}.tex: no {k}")
    body = tex.split("\\midrule\n")[1].split("\\bottomrule")[0]
    if body.count("\\\\\n") != len(rows) - 1:
        fail(f"{base}.tex: {body.count(chr(92) * 2)} rows for {len(rows) - 1} CSV rows")
    return rows


def main(d, *figures):
    run = json.load(open(os.path.join(d, "run.json")))
    for k in ("command", "build", "machine", "configuration", "counters"):
        if k not in run:
            fail(f"run.json: no {k}")
    for k in ("git_revision", "git_dirty", "compiler", "build_type", "flags"):
        if k not in run["build"]:
            fail(f"run.json: build has no {k}")
    manifest = json.load(open(os.path.join(d, "manifest.json")))
    names = [t["name"] for t in manifest["tables"]]
    if not names:
        fail("manifest.json lists no table")
    for n in names:
        check_table(d, n)
    for f in manifest["data"]:
        if not os.path.isfile(os.path.join(d, f["file"])):
            fail(f"manifest.json lists {f['file']}, which does not exist")
    readme = open(os.path.join(d, "README.md")).read()
    for link in re.findall(r"\]\(([^)]+)\)", readme):
        if not link.startswith("http") and not os.path.exists(os.path.join(d, link)):
            fail(f"README.md links {link}, which does not exist")
    shown = {n for n, _ in re.findall(r"!\[([^\]]+)\]\(figures/([^)]+)\.png\)", readme)}
    listed = {f["name"] for f in manifest["figures"]}
    if shown != listed:
        fail(f"README shows figures {sorted(shown)}, the manifest lists {sorted(listed)}")
    missing = set(figures) - listed
    if missing:
        fail(f"figures {sorted(missing)} expected, not in the manifest")
    for name in listed:
        check_png(os.path.join(d, "figures", name + ".png"))
        check_pdf(os.path.join(d, "figures", name + ".pdf"))
    print(f"check_report: {d}: {len(names)} tables x 3 formats, {len(shown)} figures x 2, "
          f"run.json, README links: well-formed")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
