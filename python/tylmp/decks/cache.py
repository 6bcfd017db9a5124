"""The specimen cache (docs/specimen.md, "Decks and the specimen cache"): inputs/common/
specimen.in calls `specimen_cache`, which reuses a cached specimen prepared with the same key or
has the deck prepare it; inputs/common/prepare.in ends with `specimen_commit`, which moves the
freshly written restart file onto its final name."""

import ast
import hashlib
import json
import os
import re

from .. import specimen
from .session import (command_line_vars, defined_variables, fail, fail_one, lammps_at, say,
                      variable_values, world_rank)

# fragments whose text (comments and blank lines dropped) is part of the specimen key: the
# preparation recipe and the numerics it uses
RECIPE = ("prepare.in", "prepare_damped.in", "prepare_two_stage.in", "numerics.in", "pair.in")
# variables the cache itself sets or that do not change the prepared state
# (the preparation's fix cell/servo outputs, v_iso_p, v_iso_Z, ..., which the fragments read,
# exist only while that fix does: defined_variables leaves them out of the settings)
# (the shearing law does not key the specimen: the preparation always uses thornton/yin,
# common/pair.in)
NOT_KEYED = {"specimen_file", "specimen_tmp", "specimen_stem", "specimen_dir", "tylmp_common",
             "tylmp_prepare", "contact_mu", "contact_gamma", "material", "prep_progress",
             "law", "contact_law", "contact_stage"}

_pending = {}           # specimen path -> key and settings, for specimen_commit


def _strip_comments(text):
    lines = (line.split("#", 1)[0].rstrip() for line in text.splitlines())
    return "\n".join(line for line in lines if line)


def _code_without_docstrings(path):
    """The generator's code as an AST dump without docstrings: edits of its prose do not
    invalidate caches, any change of code does."""
    with open(path, encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(body, list) and body and isinstance(body[0], ast.Expr)
                and isinstance(getattr(body[0], "value", None), ast.Constant)
                and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree)


def _referenced(text):
    """Variable names a fragment reads (${name}, v_name), less the equal-style formulas it
    defines itself (derived from the others: the fragment's text is hashed)."""
    text = _strip_comments(text)
    read = set(re.findall(r"\$\{(\w+)\}", text)) | set(re.findall(r"\bv_(\w+)", text))
    return read - set(re.findall(r"\bvariable\s+(\w+)\s+equal\b", text))


def prep_key(settings, common):
    """Hash of the settings and of the recipe (fragments and generator): equal keys, equal
    prepared specimens."""
    h = hashlib.sha256()
    h.update(json.dumps(settings, sort_keys=True).encode())
    for name in RECIPE:
        with open(os.path.join(common, name), encoding="utf-8") as fh:
            h.update(_strip_comments(fh.read()).encode())
    for module in specimen.GENERATOR_MODULES:
        h.update(_code_without_docstrings(module.__file__).encode())
    return h.hexdigest()


def _sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def check_cached(path, key, settings=None):
    """None if `path` is a complete specimen prepared with `key`, else why it is not."""
    record = path + ".json"
    if not os.path.exists(path):
        return "none cached"
    try:
        with open(record, encoding="utf-8") as fh:
            meta = json.load(fh)
    except (OSError, ValueError):
        return f"{os.path.basename(record)}, the record of its settings, is missing or unreadable"
    size = os.path.getsize(path)
    if size != meta.get("bytes"):
        return f"the cached file is torn: {size} bytes, its record says {meta.get('bytes')}"
    if _sha256(path) != meta.get("sha256"):
        return "the cached file does not match its record (sha256 differs)"
    if meta.get("key") != key:
        old, new = meta.get("settings", {}), settings or {}
        changed = [f"{k} {old.get(k)} -> {new.get(k)}"
                   for k in sorted(set(old) | set(new)) if old.get(k) != new.get(k)]
        if changed:
            return "it was prepared with other settings (" + ", ".join(changed) + ")"
        return "it was prepared by another version of the preparation recipe"
    return None



def specimen_cache(ptr, common):
    """Decide between reusing and preparing the specimen; set specimen_file, specimen_stem,
    specimen_tmp and tylmp_prepare (1: include prepare.in)."""
    L = lammps_at(ptr)
    names = set()
    for name in RECIPE:
        with open(os.path.join(common, name), encoding="utf-8") as fh:
            names.update(_referenced(fh.read()))
    names = defined_variables(L, sorted((names | {"specimen", "scale"}) - NOT_KEYED))
    settings = variable_values(L, names)
    kind, _, table = settings.get("distribution", "").partition(":")
    if kind in specimen.TABLES and os.path.isfile(table):
        # a size table is keyed on its content, not on its name
        settings["distribution_sha256"] = _sha256(table)
    directory = variable_values(L, ["specimen_dir"])["specimen_dir"]
    key = prep_key(settings, common)
    # the standard preparation keeps the short name; a setting given on the command line
    # gets its own file, so that variants do not overwrite one another
    stem = f"{settings['specimen']}_{settings['scale']}"
    if set(settings) & command_line_vars() - {"specimen", "scale"}:
        stem += "_" + key[:10]
    path = os.path.join(directory, stem + ".restart")
    why = check_cached(path, key, settings)
    summary = ", ".join(f"{k} {v}" for k, v in sorted(settings.items()))
    if why is None:
        say(L, f"reusing specimen {path} ({summary})")
    else:
        # every rank alike (a failure is then the same on all of them); a leftover path.tmp of
        # a killed run is overwritten by write_restart
        try:
            os.makedirs(directory or ".", exist_ok=True)
            for stale in (path, path + ".json"):
                try:
                    os.remove(stale)
                except FileNotFoundError:
                    pass
        except OSError as err:
            fail(L, f"specimen_dir {directory}: cannot prepare the specimen there ({err})")
        say(L, f"preparing specimen {path}: {why} ({summary})")
    L.command(f'variable specimen_file string "{path}"')
    L.command(f'variable specimen_stem string "{os.path.join(directory, stem)}"')
    L.command(f'variable specimen_tmp string "{path}.tmp"')
    L.command(f"variable tylmp_prepare equal {0 if why is None else 1}")
    _pending[path] = {"key": key, "settings": settings}



def specimen_commit(ptr, tmp, path):
    """After `write_restart tmp`: record the file's size, hash and settings next to it, then
    rename it onto `path` (a run killed before this leaves no file under the final name)."""
    L = lammps_at(ptr)
    if world_rank(L) == 0:
        try:
            meta = dict(_pending.get(path, {}), bytes=os.path.getsize(tmp), sha256=_sha256(tmp))
            record_tmp = path + ".json.tmp"
            with open(record_tmp, "w", encoding="utf-8") as fh:
                json.dump(meta, fh, indent=1, sort_keys=True)
                fh.write("\n")
                fh.flush()
                os.fsync(fh.fileno())
            with open(tmp, "rb") as fh:
                os.fsync(fh.fileno())
            os.replace(record_tmp, path + ".json")
            os.replace(tmp, path)
        except OSError as err:
            fail_one(L, f"cannot store the specimen {path} ({err}); nothing was put under that "
                        "name")
    say(L, f"wrote specimen {path}")

