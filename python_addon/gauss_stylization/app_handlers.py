"""Blender's application handlers (bpy.app.handlers) that a module of the add-on keeps, given as
``((list name, function), ...)``: added once when the add-on registers, removed when it unregisters."""
import bpy


def add(pairs):
    for name, handler in pairs:
        handlers = getattr(bpy.app.handlers, name)
        if handler not in handlers:
            handlers.append(handler)


def remove(pairs):
    for name, handler in pairs:
        handlers = getattr(bpy.app.handlers, name)
        if handler in handlers:
            handlers.remove(handler)
