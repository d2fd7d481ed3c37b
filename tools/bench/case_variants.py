"""A case file with some of its keys changed, for benchmarks that compare variants of one shipped case."""
import os

import yaml

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def variant_case(case, path, overrides):
    """Writes to `path` the case file `case` with `overrides` set, a mapping of dotted keys (or its YAML text, e.g.
    `{schemes.convection: lust}`; None: the case as it is), its repository-relative paths made absolute. Returns
    `path`."""
    with open(case) as f:
        data = yaml.safe_load(f.read().replace("../../../", ROOT + "/"))
    if isinstance(overrides, str):
        overrides = yaml.safe_load(overrides)
    for key, value in (overrides or {}).items():
        node, *keys = data, *key.split(".")
        for k in keys[:-1]:
            node = node[k]
        node[keys[-1]] = value
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        yaml.safe_dump(data, f, sort_keys=False)
    return path
