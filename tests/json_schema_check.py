"""What kdop's schema tests share: a schema's validator, checked against its metaschema, and a
document's errors printed one per line (jsonschema, Debian's python3-jsonschema)."""
import json

import jsonschema


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def validator_for_file(schema_path):
    schema = load_json(schema_path)
    validator_class = jsonschema.validators.validator_for(schema)
    validator_class.check_schema(schema)
    return validator_class(schema)


def print_errors(validator, path, document):
    """Prints each of `document`'s errors, naming `path` and the key; returns whether it has any."""
    errors = sorted(validator.iter_errors(document), key=lambda e: list(e.path))
    for error in errors:
        print(f"{path}: {'/'.join(map(str, error.path))}: {error.message}")
    return bool(errors)
