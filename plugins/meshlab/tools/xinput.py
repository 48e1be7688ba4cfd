#!/usr/bin/env python3
"""Moves the pointer and clicks on an X display through the XTEST extension
(ctypes on libX11/libXtst; no xdotool needed). For the GUI screenshot.

    DISPLAY=:N xinput.py move X Y | click X Y [BUTTON] | drag X0 Y0 X1 Y1 | key KEYSYM"""
import ctypes
import sys
import time

x11 = ctypes.cdll.LoadLibrary("libX11.so.6")
xtst = ctypes.cdll.LoadLibrary("libXtst.so.6")
x11.XOpenDisplay.restype = ctypes.c_void_p
x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
x11.XFlush.argtypes = [ctypes.c_void_p]
x11.XStringToKeysym.restype = ctypes.c_ulong
x11.XStringToKeysym.argtypes = [ctypes.c_char_p]
x11.XKeysymToKeycode.restype = ctypes.c_ubyte
x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_ulong]
xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
xtst.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]

display = x11.XOpenDisplay(None)
if not display:
    sys.exit("cannot open the display")
command, args = sys.argv[1], sys.argv[2:]
if command in ("move", "click"):
    xtst.XTestFakeMotionEvent(display, -1, int(args[0]), int(args[1]), 0)
    x11.XFlush(display)
    if command == "click":
        time.sleep(0.3)
        button = int(args[2]) if len(args) > 2 else 1
        xtst.XTestFakeButtonEvent(display, button, 1, 0)
        x11.XFlush(display)
        time.sleep(0.1)
        xtst.XTestFakeButtonEvent(display, button, 0, 0)
elif command == "drag":
    x0, y0, x1, y1 = (int(v) for v in args[:4])
    xtst.XTestFakeMotionEvent(display, -1, x0, y0, 0)
    x11.XFlush(display)
    time.sleep(0.3)
    xtst.XTestFakeButtonEvent(display, 1, 1, 0)
    x11.XFlush(display)
    steps = 20
    for i in range(1, steps + 1):
        time.sleep(0.03)
        xtst.XTestFakeMotionEvent(display, -1, x0 + (x1 - x0) * i // steps, y0 + (y1 - y0) * i // steps, 0)
        x11.XFlush(display)
    time.sleep(0.1)
    xtst.XTestFakeButtonEvent(display, 1, 0, 0)
elif command == "key":
    code = x11.XKeysymToKeycode(display, x11.XStringToKeysym(args[0].encode()))
    xtst.XTestFakeKeyEvent(display, code, 1, 0)
    xtst.XTestFakeKeyEvent(display, code, 0, 50)
else:
    sys.exit(__doc__)
x11.XFlush(display)
