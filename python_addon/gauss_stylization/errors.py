"""The add-on's own exceptions. Imports nothing, so every module can raise them."""


class SettingsError(ValueError):
    """A setting or the mesh cannot be stylized; the message is shown to the artist."""


class NativeModuleError(RuntimeError):
    """The solver module cannot be imported (or its facts cannot be read)."""
