"""What several test files share: helpers that are not tests themselves (no test file imports
another). ``tests`` is on pytest's ``pythonpath`` (pyproject.toml), so this is ``support``."""
