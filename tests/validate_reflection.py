#!/usr/bin/env python3
"""Validates kdop's reflection JSON files against docs/reflection.schema.json with the jsonschema
package (Debian's python3-jsonschema), and shows the schema can fail: the same document with a
binding's type misspelled, a required key dropped or an unknown key added is refused.

Usage: validate_reflection.py SCHEMA JSON...
"""
import copy
import sys

from json_schema_check import load_json, print_errors, validator_for_file


def main():
    schema_path, documents = sys.argv[1], sys.argv[2:]
    validator = validator_for_file(schema_path)
    for path in documents:
        document = load_json(path)
        if print_errors(validator, path, document):
            return 1
        entries = document["entries"]
        if not entries:
            print(f"{path}: no entries")
            return 1
        print(f"{path}: valid, {len(entries)} entries")

        # Three broken copies the schema must refuse.
        with_binding = next((e for e in entries if e["bindings"]), None)
        broken = []
        if with_binding is not None:
            wrong_type = copy.deepcopy(document)
            next(e for e in wrong_type["entries"] if e["bindings"])["bindings"][0]["type"] = "combined image sampler"
            broken.append(("a binding type with spaces", wrong_type))
        missing = copy.deepcopy(document)
        del missing["entries"][0]["spirv"]
        broken.append(("an entry without spirv", missing))
        extra = copy.deepcopy(document)
        extra["entries"][0]["stages"] = 32
        broken.append(("an unknown key", extra))
        for what, document_copy in broken:
            if validator.is_valid(document_copy):
                print(f"{path}: the schema accepts {what}")
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
