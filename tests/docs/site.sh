#!/usr/bin/env bash
# The manual: docs/commands.md is the program's --help and docs/python-api.md the module's
# docstrings, as committed; the site builds with MkDocs
# in strict mode (a page in the navigation that does not exist, or a link to a missing page, is
# an error), every link inside the built site reaches its page and anchor, and every relative
# link of the README reaches a file.
# Usage: site.sh SCATTERLAB SOURCE_DIR PYTHON_MODULE_DIR
set -uo pipefail
exe=$(realpath "$1")
src=$(realpath "$2")
module=$(realpath "$3")
source "$src/tests/cli/harness.sh"

if diff <("$src/scripts/command_reference.sh" "$exe") "$src/docs/commands.md" >"$scratch/diff"; then
  pass
else
  fail "docs/commands.md is not scripts/command_reference.sh's output: $(head -5 "$scratch/diff")"
fi

if diff <(PYTHONPATH=$module /usr/bin/python3 "$src/scripts/python_reference.py") \
     "$src/docs/python-api.md" >"$scratch/diff"; then
  pass
else
  fail "docs/python-api.md is not scripts/python_reference.py's output: $(head -5 "$scratch/diff")"
fi

if (cd "$src" && mkdocs build --strict --site-dir "$work/site") >"$scratch/mkdocs.log" 2>&1; then
  pass
else
  fail "mkdocs build --strict: $(grep -E "WARNING|ERROR|Error" "$scratch/mkdocs.log" | head -5)"
fi

/usr/bin/python3 - "$work/site" "$src" >"$scratch/links.log" 2>&1 <<'PY' && pass || fail "$(cat "$scratch/links.log")"
import html.parser
import re
import sys
from pathlib import Path
from urllib.parse import unquote, urldefrag, urljoin

site, src = Path(sys.argv[1]), Path(sys.argv[2])


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        for key in ("href", "src"):
            if key in attrs and tag in ("a", "img"):
                self.links.append(attrs[key])


pages = {}
for path in site.rglob("*.html"):
    if path.name == "404.html":
        continue  # its links are from the site's root, wherever it is served
    page = Page()
    page.feed(path.read_text(encoding="utf-8"))
    pages[path] = page

problems = []
for path, page in pages.items():
    base = "file://" + str(path)
    for link in page.links:
        if re.match(r"^[a-z]+:", link) or link.startswith("//"):
            continue  # another site: not checked (CI has no network)
        target, anchor = urldefrag(urljoin(base, link))
        target = Path(unquote(target[len("file://"):]))
        if target.is_dir():
            target = target / "index.html"
        if not target.exists():
            problems.append(f"{path.relative_to(site)}: {link}: no such page")
        elif anchor and target in pages and anchor not in pages[target].ids:
            problems.append(f"{path.relative_to(site)}: {link}: no such anchor")
readme = (src / "README.md").read_text(encoding="utf-8")
for link in re.findall(r"\]\(([^)]+)\)", readme):
    if not re.match(r"^[a-z]+:", link) and not (src / link.split("#")[0]).exists():
        problems.append(f"README.md: {link}: no such file")
print("\n".join(problems))
sys.exit(1 if problems else 0)
PY

report "docs site"
