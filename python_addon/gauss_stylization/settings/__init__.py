"""Settings: every setting written once (schema.py) and what is derived from it.

The field kinds (fields.py), the PropertyGroups saved as ``Object.gauss_stylization`` (properties.py),
the JSON round-trip and settings writer (settings_io.py), the checks before a run (validation.py) and
style slots as solver styles (styles.py). Imports errors.py and native.py only.
"""
