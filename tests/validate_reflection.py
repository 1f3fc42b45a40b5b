#!/usr/bin/env python3
"""Validates kdop's reflection JSON files against docs/reflection.schema.json with the jsonschema
package (Debian's python3-jsonschema), and shows the schema can fail: the same document with a
binding's type misspelled, a required key dropped or an unknown key added is refused.

Usage: validate_reflection.py SCHEMA JSON...
"""
import copy
import json
import sys

import jsonschema


def main():
    schema_path, documents = sys.argv[1], sys.argv[2:]
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    validator = validator_class(schema)
    for path in documents:
        with open(path, encoding="utf-8") as f:
            document = json.load(f)
        errors = sorted(validator.iter_errors(document), key=lambda e: list(e.path))
        for error in errors:
            print(f"{path}: {'/'.join(map(str, error.path))}: {error.message}")
        if errors:
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
