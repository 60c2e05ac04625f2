"""Headless Chromium driven over the DevTools protocol on a pipe (``--remote-debugging-pipe``).

Why this and not Playwright: the Debian ``chromium`` package is all it needs; the protocol runs over two
file descriptors (3: commands in, 4: replies out, NUL-separated JSON), so there is no port, no websocket
library and no browser download. It loads a page (on screen, or as it prints), collects console errors, uncaught
exceptions and failed loads, takes a full-page screenshot and returns the page's text and what a probe (a script
run in the page) measured of its layout.
"""

from __future__ import annotations

import base64
import fcntl
import json
import os
import select
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from clutchopt.report.pdf import find_chromium

__all__ = ["find_chromium", "render", "Rendered"]


@dataclass
class Rendered:
    text: str  # document.body.innerText
    errors: list[str] = field(default_factory=list)  # console errors, uncaught exceptions, failed loads
    probed: object = None  # what the probe returned (JSON)


class _DevTools:
    def __init__(self, binary: str, profile: str):
        commands_read, self._commands = os.pipe()
        self._replies, replies_write = os.pipe()

        def wire_descriptors():  # in the child: commands on fd 3, replies on fd 4
            high_in = fcntl.fcntl(commands_read, fcntl.F_DUPFD, 10)
            high_out = fcntl.fcntl(replies_write, fcntl.F_DUPFD, 10)
            os.dup2(high_in, 3)
            os.dup2(high_out, 4)

        self.process = subprocess.Popen(
            [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
             "--disable-extensions", "--remote-debugging-pipe", f"--user-data-dir={profile}", "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=wire_descriptors, close_fds=False)
        os.close(commands_read)
        os.close(replies_write)
        self._buffer = b""
        self._next_id = 0
        self.events: list[dict] = []

    def call(self, method: str, session: str | None = None, timeout: float = 30.0, **params) -> dict:
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._commands, json.dumps(message).encode() + b"\0")
        while True:
            reply = self._receive(timeout)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]
            self.events.append(reply)

    def wait_for(self, event: str, timeout: float = 30.0) -> dict:
        while True:
            for seen in self.events:
                if seen.get("method") == event:
                    return seen
            self.events.append(self._receive(timeout))

    def _receive(self, timeout: float) -> dict:
        deadline = time.monotonic() + timeout
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self._replies], [], [], left)[0]:
                raise TimeoutError("no answer from Chromium")
            chunk = os.read(self._replies, 1 << 20)
            if not chunk:
                raise RuntimeError("Chromium closed the DevTools pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def close(self) -> None:
        try:
            self.call("Browser.close", timeout=5)
        except (RuntimeError, TimeoutError, OSError):
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
        os.close(self._commands)
        os.close(self._replies)


def render(page: Path, screenshot: Path, width: int = 1200, media: str = "screen", probe: str | None = None) -> Rendered:
    """Load ``page`` in headless Chromium ``width`` px wide, as on ``media`` ("screen" or "print"), write a full-page
    PNG to ``screenshot``, report errors and text, and what the script ``probe`` (an expression whose value is JSON
    text) returned."""
    binary = find_chromium()
    if binary is None:
        raise FileNotFoundError("no Chromium found")
    with tempfile.TemporaryDirectory() as profile:
        tools = _DevTools(binary, profile)
        try:
            target = tools.call("Target.createTarget", url="about:blank")["targetId"]
            session = tools.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
            for domain in ("Runtime", "Log", "Page"):
                tools.call(f"{domain}.enable", session)
            tools.call("Emulation.setDeviceMetricsOverride", session, width=width, height=900, deviceScaleFactor=1,
                       mobile=False)
            tools.call("Emulation.setEmulatedMedia", session, media=media)
            tools.call("Page.navigate", session, url=page.resolve().as_uri())
            tools.wait_for("Page.loadEventFired")

            def evaluate(expression: str):
                return tools.call("Runtime.evaluate", session, expression=expression,
                                  returnByValue=True)["result"]["value"]
            text = evaluate("document.body.innerText")
            probed = json.loads(evaluate(probe)) if probe else None
            shot = tools.call("Page.captureScreenshot", session, format="png", captureBeyondViewport=True)
            screenshot.write_bytes(base64.b64decode(shot["data"]))
        finally:
            tools.close()
    return Rendered(text, _errors(tools.events), probed)


def _errors(events: list[dict]) -> list[str]:
    errors = []
    for event in events:
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            errors.append(details.get("exception", {}).get("description") or details.get("text", "exception"))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            errors.append(" ".join(str(arg.get("value", arg.get("description", ""))) for arg in params["args"]))
        elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
            errors.append(params["entry"]["text"])
    return errors
