#!/usr/bin/env python3
"""Validates resolve-bindings maps (kdop taa --resolve-bindings) against
docs/resolve-bindings.schema.json with the jsonschema package, and shows the schema can fail: each
map with a role misspelled, the format dropped or an unknown key added is refused.

Usage: validate_resolve_bindings.py SCHEMA MAP...
"""
import copy
import json
import sys

import jsonschema


def main():
    schema_path, maps = sys.argv[1], sys.argv[2:]
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    for path in maps:
        with open(path, encoding="utf-8") as f:
            document = json.load(f)
        errors = list(validator.iter_errors(document))
        for error in errors:
            print(f"{path}: {'/'.join(map(str, error.path))}: {error.message}")
        if errors:
            return 1
        misspelled = copy.deepcopy(document)
        name = next(iter(misspelled["resources"]))
        misspelled["resources"][name] = "curent"
        dropped = copy.deepcopy(document)
        del dropped["format"]
        unknown = copy.deepcopy(document)
        unknown["bindings"] = {}
        for what, wrong in (("a misspelled role", misspelled), ("no format", dropped), ("an unknown key", unknown)):
            if validator.is_valid(wrong):
                print(f"{path}: the schema takes {what}")
                return 1
        print(f"{path}: valid, and the schema refuses its three wrong copies")
    return 0


if __name__ == "__main__":
    sys.exit(main())
