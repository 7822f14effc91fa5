"""The run's options: the structured root attribute `options_table` (format >= 1) and,
for format-0 files, the root attribute `options` (PETSc's PetscOptionsGetAll
text) parsed back into (key, value) pairs.

The text is "-key value " or "-key " (a bare flag) for every option, keys in
PETSc's sorted (strcmp) order. A value may itself hold options (-wp_configs
" -sim_ts_type rk ..."): a token that looks like an option but sorts before the
key being read belongs to that key's value, since the next real key sorts
after it. Values keep their spaces (a leading space shows as a double space).
"""
import re

_NUMBER = re.compile(r"^-(\d|\.\d|inf\b|nan\b|infinity\b)", re.IGNORECASE)


def _looks_like_key(token):
    return token.startswith("-") and len(token) > 1 and not _NUMBER.match(token)


def parse_text(text):
    """{key: value} from a PetscOptionsGetAll text (keys without the "-")."""
    tokens = text.split(" ")
    while tokens and tokens[-1] == "":
        tokens.pop()
    out = {}
    i = 0
    # text before the first key (none in nltopo's files) is skipped
    while i < len(tokens) and not _looks_like_key(tokens[i]):
        i += 1
    while i < len(tokens):
        key = tokens[i][1:]
        i += 1
        value = []
        while i < len(tokens):
            t = tokens[i]
            if _looks_like_key(t) and t[1:] > key:  # strcmp order, as PETSc sorts
                break
            value.append(t)
            i += 1
        out[key] = " ".join(value)
    return out


def parse_effective(text):
    """{key: value} of the `effective_options` attribute, one "-name value" a line."""
    out = {}
    for line in text.splitlines():
        if not line.startswith("-"):
            continue
        key, _, value = line[1:].partition(" ")
        out[key] = value
    return out


def to_command_line(options):
    """The options as one command-line string, values with spaces quoted."""
    parts = []
    for k, v in options.items():
        parts.append("-" + k)
        if v != "":
            parts.append('"' + v + '"' if (" " in v or v.startswith("-")) else v)
    return " ".join(parts)
