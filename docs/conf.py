# Sphinx configuration of the tylmp documentation site. The pages are MyST Markdown, readable
# as they are on a repository browser; the site adds the index, search and checked links.
#   sphinx-build -W --keep-going -b html docs build/docs-html
# (Debian 12: python3-sphinx 5.3, python3-myst-parser 0.18, furo 2022.12; scripts/setup.sh
# installs them). tests/test_docs_site.py builds it with -W: every warning is an error, so a
# broken page link, heading anchor or image fails the suite.
import re

from pygments.lexer import RegexLexer, bygroups
from pygments.token import Comment, Keyword, Name, Number, String, Text, Whitespace

project = "tylmp"
author = "the tylmp authors"
copyright = "the tylmp authors; GNU General Public License, version 2"

extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
root_doc = "index"
# docs/validation/summary.md is the table `tyanalysis compare` writes; validation.md links it
# as a file of records, not as a page
exclude_patterns = ["_build", "validation/summary.md"]

# `page.md#section` links: anchors of headings down to level 4, the slugs GitHub makes, so
# that one link works on the repository browser and in the site; a broken one is a warning
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath"]
# a link with no scheme is a cross-reference that must resolve
nitpicky = True
suppress_warnings = []

html_theme = "furo"
html_title = "tylmp"
html_static_path = []
html_show_sourcelink = False
html_last_updated_fmt = None

# fences without a language are decks, shell lines or tables of numbers: no highlighting
highlight_language = "text"


class LammpsLexer(RegexLexer):
    """LAMMPS input decks: the command word, comments, variables, numbers."""

    name = "LAMMPS"
    aliases = ["lammps"]
    filenames = ["*.in"]
    tokens = {
        "root": [
            (r"#.*$", Comment.Single),
            (r"^(\s*)([a-z_]+)", bygroups(Whitespace, Keyword)),
            (r"\$\{[^}]*\}|\$[A-Za-z]|v_\w+|c_\w+(\[\d+\])?|f_\w+(\[\d+\])?", Name.Variable),
            (r'"[^"]*"' + "|'[^']*'", String),
            (r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\b", Number),
            (r"\s+", Whitespace),
            (r"\S", Text),
        ],
    }


def setup(app):
    app.add_lexer("lammps", LammpsLexer)
    return {"parallel_read_safe": True}
