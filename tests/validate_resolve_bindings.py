#!/usr/bin/env python3
"""Validates resolve-bindings maps (kdop taa --resolve-bindings) against
docs/resolve-bindings.schema.json with the jsonschema package, and shows the schema can fail: each
map with a role misspelled, the format dropped or an unknown key added is refused.

Usage: validate_resolve_bindings.py SCHEMA MAP...
"""
import copy
import sys

from json_schema_check import load_json, print_errors, validator_for_file


def main():
    schema_path, maps = sys.argv[1], sys.argv[2:]
    validator = validator_for_file(schema_path)
    for path in maps:
        document = load_json(path)
        if print_errors(validator, path, document):
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
