"""Keyword arguments to a scene's TOML text.

The module runs scenes, not a second set of options: ``simulate(albedo=0.9, photons=1e5)`` is
the scene ``[medium] albedo = 0.9``, ``[run] photons = 1e5``, parsed by the same C++ reader as
``scatterlab simulate --scene`` (include/scatterlab/io/scene.hpp), so every key is checked and
every error names its field the same way. A keyword is either

* a table of the scene given whole as a dict: ``medium={"albedo": 0.9, "g": 0.5}``,
  ``grid={"r": {"max": 2, "bins": 20}}``, ``layers=[{...}, ...]`` for the slab's ``[[layers]]``,
  ``tally=[{"name": ..., "score": ..., "filters": {...}}, ...]`` for declared tallies;
* or a key of one table, by its own name: ``albedo=0.9`` is ``medium.albedo``; ``r={"max": 2,
  "bins": 20}`` is ``grid.r``. Which table holds which key is KEY_TABLES below, per geometry,
  read at import from the program's one table of scene keys (``scatterlab scene --keys``). Two
  names are shared by two tables and are resolved as in the command line's flags:
  ``source="point"`` is ``source.type`` and ``geometry="sphere"`` is ``geometry.type``; a
  sphere's ``length_unit`` is ``medium.length_unit``, a slab's ``geometry.length_unit``.

Dicts merge into what a scene file (``scene="file.toml"``) gives, key by key; anything else
replaces it.
"""

from __future__ import annotations

import difflib
import json
import math
import numbers
import os
import re
import tomllib
from pathlib import Path
from typing import Any

from ._scatterlab import read_scene_file as read_scene_text
from ._scatterlab import scene_keys

def _key_tables() -> tuple[tuple[str, ...], dict[str, dict[str, str]]]:
    """The scene's tables, and per geometry.type {key: table}, from the program's one table of
    scene keys (io/scene_schema.hpp). A key of two tables of one geometry (a sphere's
    geometry.radius and source.radius) goes to the first, as the reference lists them; the other
    is given as a whole table (``source={"radius": 0.5}``)."""
    tables: list[str] = []
    key_tables: dict[str, dict[str, str]] = {}
    for path, geometries in scene_keys():
        table, key = path.split(".")[:2]
        if table not in tables:
            tables.append(table)
        for geometry in geometries:
            keys = key_tables.setdefault(geometry, {})
            # geometry= and source= name their type; [[layers]], [[tally]], [mesh] and
            # [output] are whole tables (layers=[{...}], tally=[{...}], out=).
            if key != "type" and table not in ("layers", "tally", "mesh", "output"):
                keys.setdefault(key, table)
    return tuple(tables), key_tables


TABLES, KEY_TABLES = _key_tables()


def _merge(into: dict, update: dict) -> None:
    """Merges ``update`` into ``into``: dicts key by key, anything else replaced."""
    for key, value in update.items():
        if isinstance(value, dict) and isinstance(into.get(key), dict):
            _merge(into[key], value)
        else:
            into[key] = value


def scene_dict(geometry: str | None, scene: str | Path | None,
               keys: dict[str, Any]) -> tuple[str, dict, str]:
    """The scene as a dict, its geometry and its origin, which names the text in the reader's
    messages: "keywords", or "FILE with keywords" (the positions in a message are then those
    of scene_text's text, not of the file).

    ``geometry``: the geometry the caller runs (searchlight: "half_space"), or None to take it
    from the keywords or the scene file as the command line does ("infinite" without one).
    """
    doc: dict = {}
    origin = "keywords"
    if scene is not None:
        origin = f"{scene} with keywords" if keys else str(scene)
        try:
            doc = tomllib.loads(read_scene_text(os.fspath(scene)))
        except tomllib.TOMLDecodeError as e:
            if not keys:  # read as written: the scene reader reports it, as for the program
                doc = {}
            else:
                raise ValueError(f"scene: {scene}: {e}; accepted: a TOML scene file") from None
    return apply_keys(doc, geometry, keys), doc, origin


def apply_keys(doc: dict, geometry: str | None, keys: dict[str, Any]) -> str:
    """Lays the keywords over the scene dict ``doc``, in place, and returns its geometry (the
    caller's, else the keywords', else the scene's, else "infinite")."""
    given = keys.get("geometry")
    if isinstance(given, str):
        given = {"type": given}
    if geometry is None:
        geometry = (given or {}).get("type") or doc.get("geometry", {}).get("type") or "infinite"
    tables = KEY_TABLES.get(geometry)
    if tables is None:
        raise ValueError(f"geometry.type: got {geometry!r}; accepted: "
                         f"{', '.join(KEY_TABLES)}")
    for key, value in keys.items():
        if key in ("geometry", "source") and isinstance(value, str):
            _merge(doc, {key: {"type": value}})
        elif key in TABLES:
            if key in ("layers", "tally"):  # arrays of tables
                doc[key] = value
            elif isinstance(value, dict):
                _merge(doc, {key: value})
            else:
                raise ValueError(f"{key}: got {value!r}; accepted: a dict, the scene's [{key}] "
                                 f"table")
        elif key in tables:
            _merge(doc, {tables[key]: {key: value}})
        else:
            names = sorted(set(tables) | set(TABLES) | {"scene", "out"})
            nearest = difflib.get_close_matches(key, names, n=1)
            hint = f', did you mean "{nearest[0]}"?' if nearest else ""
            raise ValueError(f"{key}: unknown keyword for the geometry {geometry!r}{hint}; "
                             f"accepted: {', '.join(names)}")
    # The text names its geometry, so that it reads the same on its own (scatterlab simulate).
    doc.setdefault("geometry", {}).setdefault("type", geometry)
    order = {table: i for i, table in enumerate(TABLES)}
    ordered = sorted(doc.items(), key=lambda item: order.get(item[0], -1))
    doc.clear()
    doc.update(ordered)
    return geometry


def _key(key: str) -> str:
    """A TOML key: bare when it can be, else quoted (so that a misspelt key reaches the reader
    as written, and is named in its error)."""
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _value(value: Any, key: str) -> str:
    """One TOML value: bool, integer, float (inf, nan), string, array or inline table."""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, (str, Path)):
        return json.dumps(str(value))  # JSON's escapes are TOML's
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(v, f'{key}.{k}')}"
                               for k, v in value.items()) + "}"
    if hasattr(value, "tolist"):  # numpy arrays and scalars
        return _value(value.tolist(), key)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v, key) for v in value) + "]"
    raise ValueError(f"{key}: got {value!r} of type {type(value).__name__}; accepted: a "
                     f"number, bool, string, list or dict")


def to_toml(doc: dict) -> str:
    """The scene dict as TOML text: top-level tables, ``[[layers]]`` for lists of tables."""
    lines = []
    # Top-level keys first: after a table's header they would belong to the table.
    items = sorted(doc.items(), key=lambda item: isinstance(item[1], (dict, list)))
    for table, body in items:
        if isinstance(body, list) and all(isinstance(item, dict) for item in body) and body:
            for item in body:
                lines.append(f"[[{_key(table)}]]")
                lines += [f"{_key(k)} = {_value(v, f'{table}.{k}')}" for k, v in item.items()]
        elif isinstance(body, dict):
            lines.append(f"[{_key(table)}]")
            lines += [f"{_key(k)} = {_value(v, f'{table}.{k}')}" for k, v in body.items()]
        else:
            lines.append(f"{_key(table)} = {_value(body, table)}")
    return "\n".join(lines) + "\n"
