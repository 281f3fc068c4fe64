"""Pin handles in a live run: the pins as handles to drag (handles.py) and the viewport tool that
grabs, drags and draws them (handle_tool.py). Imports run/ and the layers below it.
"""
