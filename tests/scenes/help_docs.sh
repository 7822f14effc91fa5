# The documentation holds together: every relative link in README.md and
# docs/ (pages and images) resolves to a file of the source tree, every
# #anchor to a heading of its page, and README.md links every docs page
# (checks/help_docs.py).
source "$(dirname "$0")/common.bash"
$PY "$CHECKS/help_docs.py" links "$SRC"
