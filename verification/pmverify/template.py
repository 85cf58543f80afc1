"""Case files made from an example's case.toml: the example stays the one source of every choice, a
script only sets the keys it varies. Edits keep comments and layout; each must hit exactly one place,
else the template changed under the script and it stops with a message naming both.

    t = CaseTemplate("examples/b6_fracture_block_3d/case.toml")
    text = t.set({"mesh.cells": [24, 16, 4], "loading.increments": 60, "alpha.region[0].profile": "linear"})
"""

import os
import re
import tomllib

from .program import REPO


def toml_value(v):
    """A Python value as a TOML literal (bool, int, float, str, list)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML literal for {v!r}")


_HEADER = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.\-]+)\s*\]\]?\s*(#.*)?$")


class CaseTemplate:
    def __init__(self, path):
        self.path = path if os.path.isabs(path) else os.path.join(REPO, path)
        with open(self.path) as f:
            self.text = f.read()
        self.data = tomllib.loads(self.text)  # the template must itself be a valid case

    def rel(self):
        return os.path.relpath(self.path, REPO)

    def get(self, dotted):
        """A value of the template, by the same paths as set()."""
        node = self.data
        for part in _split(dotted):
            node = node[part]
        return node

    def set(self, values, text=None):
        """The template text with each `path = value` set (path: 'table.key', 'table.sub.key',
        'array.of.tables[i].key'; value: a Python value, or a raw TOML string wrapped in Raw). A key absent
        from its table is added after the table's last key. Returns the new text."""
        text = self.text if text is None else text
        for path, value in values.items():
            text = self._set_one(text, path, value)
        tomllib.loads(text)  # still valid TOML
        return text

    def _set_one(self, text, path, value):
        parts = path.split(".")
        key = parts[-1]
        table, index = ".".join(parts[:-1]), None
        m = re.match(r"^(.*)\[(\d+)\]$", table)
        if m:
            table, index = m.group(1), int(m.group(2))
        lines = text.split("\n")
        start, end = self._table_span(lines, table, index, path)
        literal = value.text if isinstance(value, Raw) else toml_value(value)
        hits = [i for i in range(start, end) if re.match(rf"^\s*{re.escape(key)}\s*=", lines[i])]
        if len(hits) > 1:
            raise RuntimeError(f"template {self.rel()}: key {path!r} is set {len(hits)} times")
        if hits:
            i = hits[0]
            m = re.match(rf"^(\s*{re.escape(key)}\s*=\s*)(.*)$", lines[i])
            comment = _trailing_comment(m.group(2))
            lines[i] = m.group(1) + literal + (("  " + comment) if comment else "")
        else:
            last = max((i for i in range(start, end) if re.match(r"^\s*[A-Za-z0-9_\-]+\s*=", lines[i])), default=start - 1)
            lines.insert(last + 1, f"{key} = {literal}")
        return "\n".join(lines)

    def _table_span(self, lines, table, index, path):
        """Lines [start, end) of the table's body: after its header, up to the next header."""
        if table == "":
            start = 0
        else:
            heads = [i for i, ln in enumerate(lines) if (m := _HEADER.match(ln)) and m.group(2) == table]
            if index is not None:
                heads = heads[index:index + 1]
            if len(heads) != 1:
                raise RuntimeError(f"template {self.rel()}: table [{table}]" + (f"[{index}]" if index is not None else "")
                                   + f" found {len(heads)} times, setting {path!r}")
            start = heads[0] + 1
        end = next((i for i in range(start, len(lines)) if _HEADER.match(lines[i])), len(lines))
        return start, end

    def replace(self, pattern, replacement, text=None):
        """Regex replacement (re.M | re.S) that must match exactly once; for edits set() cannot express
        (removing a table, replacing an [[alpha.region]] block)."""
        text = self.text if text is None else text
        new, n = re.subn(pattern, lambda m: replacement, text, flags=re.M | re.S)
        if n != 1:
            raise RuntimeError(f"template {self.rel()}: pattern {pattern!r} matched {n} times (need 1)")
        return new

    def drop_table(self, table, text=None, index=None):
        """The text without the table (its header and body; index for an array of tables)."""
        text = self.text if text is None else text
        lines = text.split("\n")
        start, end = self._table_span(lines, table, index, table)
        del lines[start - 1:end]
        return "\n".join(lines)


class Raw:
    """A TOML literal given as text (e.g. an inline table)."""

    def __init__(self, text):
        self.text = text


def _split(dotted):
    out = []
    for part in dotted.split("."):
        m = re.match(r"^(.*)\[(\d+)\]$", part)
        out += [m.group(1), int(m.group(2))] if m else [part]
    return out


def _trailing_comment(rest):
    """The '# ...' after a TOML value (not inside a string), or ''."""
    in_str = None
    for i, ch in enumerate(rest):
        if in_str:
            if ch == "\\":
                continue
            if ch == in_str:
                in_str = None
        elif ch in "\"'":
            in_str = ch
        elif ch == "#":
            return rest[i:]
    return ""
